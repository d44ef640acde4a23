// VTK XML image data: the hydrogen file written by VTK (zlib blocks, inline base64), and small
// files written here in the other layouts (uncompressed inline, appended raw with UInt64 headers,
// big-endian).
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>

#include "tests/readers/reader_test_util.h"

namespace voxlink::convert::testing {
namespace {

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = uint32_t(bytes[i]) << 16 |
                       (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += alphabet[n >> 18 & 63];
    out += alphabet[n >> 12 & 63];
    out += i + 1 < bytes.size() ? alphabet[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? alphabet[n & 63] : '=';
  }
  return out;
}

template <class T>
void append(std::vector<uint8_t>& out, T v, bool bigEndian = false) {
  const size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &v, sizeof v);
  if (bigEndian) std::reverse(out.begin() + static_cast<long>(at), out.end());
}

TEST(VtiReader, HydrogenZlibBlocks) {
  VOXLINK_REQUIRE_DATA("volume/vtk_hydrogen.vti");
  auto source = openOrDie(dataPath("volume/vtk_hydrogen.vti"));
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.format, "vti");
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{64, 64, 64}));
  EXPECT_EQ(info.type, ScalarType::kF32);
  EXPECT_EQ(info.spacing, (std::array<double, 3>{1, 1, 1}));
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  std::vector<float> v(data->size() / 4);
  std::memcpy(v.data(), data->data(), data->size());
  // The DataArray's RangeMin/RangeMax attributes (written by VTK) are 0 and 1.
  EXPECT_EQ(*std::min_element(v.begin(), v.end()), 0.0f);
  EXPECT_EQ(*std::max_element(v.begin(), v.end()), 1.0f);
  // Computed outside this project with Python (base64, zlib, struct; sum in index order).
  double sum = 0;
  for (float f : v) sum += f;
  EXPECT_DOUBLE_EQ(sum, 4856.008970333924);
  EXPECT_EQ(std::count_if(v.begin(), v.end(), [](float f) { return f > 0; }), 249600);
}

TEST(VtiReader, UncompressedInlineBigEndianAndAppendedRawCompressed) {
  TempDir dir;
  const auto values = patternBytes(3 * 4 * 5 * 2, 41);  // int16
  // Inline, uncompressed, big-endian: UInt32 byte count then the data, one base64 run.
  std::vector<uint8_t> inline_;
  append(inline_, uint32_t(values.size()), true);
  const auto big = swapped(values, 2);
  inline_.insert(inline_.end(), big.begin(), big.end());
  std::vector<uint8_t> otherArray(inline_.begin(), inline_.begin() + 4);  // same size, other values
  otherArray.resize(inline_.size(), 0x11);
  writeText(dir.file("inline.vti"),
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\" "
            "byte_order=\"BigEndian\">\n"
            "<ImageData WholeExtent=\"2 4 0 3 10 14\" Origin=\"1 2 3\" Spacing=\"0.5 0.5 2\">\n"
            "<Piece Extent=\"2 4 0 3 10 14\"><PointData Scalars=\"v\">\n"
            "<DataArray type=\"Int16\" Name=\"other\" format=\"binary\">" +
                base64(otherArray) +
                "</DataArray>\n"
                "<DataArray type=\"Int16\" Name=\"v\" format=\"binary\">\n  " +
                base64(inline_) +
                "\n</DataArray>\n"
                "</PointData></Piece></ImageData></VTKFile>\n");
  // Appended raw, zlib in blocks of 16 bytes, UInt64 header words.
  std::vector<uint8_t> blocksHeader, packed;
  const uint64_t blockSize = 16, blocks = (values.size() + blockSize - 1) / blockSize;
  append(blocksHeader, blocks);
  append(blocksHeader, blockSize);
  append(blocksHeader, uint64_t(values.size() % blockSize));
  for (uint64_t b = 0; b < blocks; ++b) {
    const size_t n = std::min<size_t>(blockSize, values.size() - b * blockSize);
    std::vector<uint8_t> z(compressBound(n));
    uLongf zn = z.size();
    ASSERT_EQ(compress(z.data(), &zn, values.data() + b * blockSize, n), Z_OK);
    append(blocksHeader, uint64_t(zn));
    packed.insert(packed.end(), z.begin(), z.begin() + static_cast<long>(zn));
  }
  std::vector<uint8_t> file;
  const std::string head =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\" "
      "compressor=\"vtkZLibDataCompressor\">\n<ImageData WholeExtent=\"2 4 0 3 10 14\" Origin=\"1 "
      "2 3\" Spacing=\"0.5 0.5 2\">\n"
      "<Piece Extent=\"2 4 0 3 10 14\"><PointData><DataArray type=\"Int16\" Name=\"v\" "
      "format=\"appended\" offset=\"0\"/>"
      "</PointData></Piece></ImageData>\n<AppendedData encoding=\"raw\">\n   _";
  file.insert(file.end(), head.begin(), head.end());
  file.insert(file.end(), blocksHeader.begin(), blocksHeader.end());
  file.insert(file.end(), packed.begin(), packed.end());
  const std::string tail = "\n</AppendedData>\n</VTKFile>\n";
  file.insert(file.end(), tail.begin(), tail.end());
  writeBytes(dir.file("appended.vti"), file);

  for (const char* name : {"inline.vti", "appended.vti"}) {
    SCOPED_TRACE(name);
    auto source = openOrDie(dir.file(name));
    ASSERT_TRUE(source);
    EXPECT_EQ(source->info().dims, (std::array<uint32_t, 3>{3, 4, 5}));
    EXPECT_EQ(source->info().type, ScalarType::kI16);
    EXPECT_EQ(source->info().spacing, (std::array<double, 3>{0.5, 0.5, 2}));
    EXPECT_EQ(source->info().origin,
              (std::array<double, 3>{1 + 2 * 0.5, 2, 3 + 10 * 2}));  // extent minimum
    auto data = readAll(*source);
    ASSERT_TRUE(data) << data.message();
    EXPECT_TRUE(*data == values);
  }
  auto cut = readBytes(dir.file("appended.vti"));
  cut[head.size() + blocksHeader.size() + 3] ^= 0xff;
  writeBytes(dir.file("bad.vti"), cut);
  expectError(openVolume(dir.file("bad.vti")), ErrorCode::kCorrupt,
              {"bad.vti", "DataArray", "zlib block 0"});
}

}  // namespace
}  // namespace voxlink::convert::testing
