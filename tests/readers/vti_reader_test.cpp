// SPDX-License-Identifier: BSD-3-Clause
// VTK XML image data: the hydrogen file written by VTK (zlib blocks, inline base64), and small
// files written here in the other layouts (uncompressed inline, appended raw with UInt64 headers,
// big-endian).
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>

#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

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

// An uncompressed inline DataArray: UInt32 byte count and data in one base64 run.
std::string inlineArray(const std::string& name, const std::string& type, int components,
                        const std::vector<uint8_t>& bytes) {
  std::vector<uint8_t> run;
  append(run, uint32_t(bytes.size()));
  run.insert(run.end(), bytes.begin(), bytes.end());
  return "<DataArray type=\"" + type + "\" Name=\"" + name + "\" NumberOfComponents=\"" +
         std::to_string(components) + "\" format=\"binary\">" + base64(run) + "</DataArray>\n";
}

std::string imageFile(const std::string& extent, const std::string& geometry,
                      const std::string& arrays) {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" byte_order=\"LittleEndian\">\n"
         "<ImageData WholeExtent=\"" +
         extent + "\" " + geometry + ">\n<Piece Extent=\"" + extent + "\"><PointData>\n" + arrays +
         "</PointData></Piece></ImageData></VTKFile>\n";
}

TEST(VtiReader, VectorArrayFirstIsSkippedAndVariablePicksTheArray) {
  TempDir dir;
  const std::vector<uint8_t> velocity = patternBytes(2 * 2 * 2 * 3 * 4, 7);  // 3 x Float32
  const std::vector<uint8_t> density = patternBytes(2 * 2 * 2 * 2, 11);      // Int16
  const std::vector<uint8_t> mass = patternBytes(2 * 2 * 2, 13);             // UInt8
  writeText(dir.file("a.vti"), imageFile("0 1 0 1 0 1", "",
                                         inlineArray("velocity", "Float32", 3, velocity) +
                                             inlineArray("density", "Int16", 1, density) +
                                             inlineArray("mass", "UInt8", 1, mass)));
  // No --variable: the first scalar array, with a note naming every array.
  auto source = openOrDie(dir.file("a.vti"));
  ASSERT_TRUE(source);
  EXPECT_EQ(source->info().type, ScalarType::kI16);
  EXPECT_TRUE(hasNote(source->info(), "reading 'density'")) << notesOf(source->info());
  EXPECT_TRUE(hasNote(source->info(), "'velocity' (3 components)")) << notesOf(source->info());
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == density);
  // --variable picks by name.
  OpenOptions options;
  options.variable = "mass";
  source = openOrDie(dir.file("a.vti"), options);
  ASSERT_TRUE(source);
  EXPECT_EQ(source->info().type, ScalarType::kU8);
  data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == mass);
  // An unknown name lists the scalar arrays; a vector array is refused naming the attribute.
  options.variable = "pressure";
  expectError(openVolume(dir.file("a.vti"), options), ErrorCode::kInvalidArgument,
              {"a.vti", "--variable 'pressure'", "'density', 'mass'"});
  options.variable = "velocity";
  expectError(openVolume(dir.file("a.vti"), options), ErrorCode::kUnsupported,
              {"a.vti", "NumberOfComponents", "3", "'density', 'mass'"});
  // Only vector arrays: refused, listing them.
  writeText(dir.file("v.vti"),
            imageFile("0 1 0 1 0 1", "", inlineArray("velocity", "Float32", 3, velocity)));
  expectError(openVolume(dir.file("v.vti")), ErrorCode::kUnsupported,
              {"v.vti", "NumberOfComponents", "'velocity' (3 components)"});
}

// Values i + 10 j + 100 k (Int16) of a 3x4x5 grid, i fastest.
std::vector<uint8_t> indexValues() {
  std::vector<uint8_t> out;
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 3; ++i) append(out, int16_t(i + 10 * j + 100 * k));
  return out;
}

int16_t valueAt(const std::vector<uint8_t>& data, const std::array<uint32_t, 3>& dims, uint32_t x,
                uint32_t y, uint32_t z) {
  int16_t v;
  std::memcpy(&v, data.data() + 2 * ((size_t{z} * dims[1] + y) * dims[0] + x), 2);
  return v;
}

TEST(VtiReader, ReversedAndPermutedDirectionsKeepWorldPositions) {
  TempDir dir;
  const std::string arrays = inlineArray("v", "Int16", 1, indexValues());
  // x and z reversed: grid voxel (i, j, k) lies at (10 - 0.5 (1 + i), 20 + j, 30 - 2 (2 + k)).
  writeText(dir.file("flip.vti"),
            imageFile("1 3 0 3 2 6",
                      "Origin=\"10 20 30\" Spacing=\"0.5 1 2\" Direction=\"-1 0 0 0 1 0 0 0 -1\"",
                      arrays));
  auto source = openOrDie(dir.file("flip.vti"));
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{3, 4, 5}));
  EXPECT_EQ(info.spacing, (std::array<double, 3>{0.5, 1, 2}));
  // The stored grid's first voxel is the grid's (2, 0, 4): the smallest x and z.
  EXPECT_EQ(info.origin, (std::array<double, 3>{10 - 0.5 * 3, 20, 30 - 2 * 6}));
  EXPECT_TRUE(hasNote(info, "-x +y -z")) << notesOf(info);
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  for (uint32_t z = 0; z < 5; ++z)
    for (uint32_t y = 0; y < 4; ++y)
      for (uint32_t x = 0; x < 3; ++x)
        EXPECT_EQ(valueAt(*data, info.dims, x, y, z), (2 - x) + 10 * y + 100 * (4 - z));

  // Grid axis 0 along +y, axis 1 along -x: stored x is the grid's j reversed, stored y its i.
  writeText(
      dir.file("swap.vti"),
      imageFile("0 2 0 3 0 4",
                "Origin=\"1 2 3\" Spacing=\"0.5 1 2\" Direction=\"0 -1 0 1 0 0 0 0 1\"", arrays));
  source = openOrDie(dir.file("swap.vti"));
  ASSERT_TRUE(source);
  const VolumeInfo& swapped = source->info();
  EXPECT_EQ(swapped.dims, (std::array<uint32_t, 3>{4, 3, 5}));
  EXPECT_EQ(swapped.spacing, (std::array<double, 3>{1, 0.5, 2}));
  EXPECT_EQ(swapped.origin, (std::array<double, 3>{1 - 3, 2, 3}));
  data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  for (uint32_t z = 0; z < 5; ++z)
    for (uint32_t y = 0; y < 3; ++y)
      for (uint32_t x = 0; x < 4; ++x)
        EXPECT_EQ(valueAt(*data, swapped.dims, x, y, z), y + 10 * (3 - x) + 100 * z);
}

}  // namespace
}  // namespace voxlink::sources::testing

namespace voxlink::sources::testing {
namespace {

// The header is parsed by pugixml: broken or cut XML is one line naming the file and the
// element, entity references are decoded, and deep nesting is no danger.
TEST(VtiReader, HeaderXmlErrorsNameTheFileAndTheElement) {
  TempDir dir;
  const std::vector<uint8_t> mass = patternBytes(2 * 2 * 2, 13);
  const std::string good = imageFile("0 1 0 1 0 1", "", inlineArray("m&amp;n", "UInt8", 1, mass));
  OpenOptions options;
  options.variable = "m&n";
  writeText(dir.file("entity.vti"), good);
  auto source = openOrDie(dir.file("entity.vti"), options);
  ASSERT_TRUE(source);
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  EXPECT_TRUE(*data == mass);

  std::string broken = good;
  broken.replace(broken.find("Name="), 5, "Name");  // an attribute without '='
  writeText(dir.file("broken.vti"), broken);
  const auto error = openVolume(dir.file("broken.vti"));
  expectError(error, ErrorCode::kCorrupt, {"broken.vti", "XML at byte", "<DataArray>"});
  EXPECT_EQ(error.message().find('\n'), std::string::npos);

  writeText(dir.file("cut.vti"), good.substr(0, good.find("<Piece")));
  expectError(openVolume(dir.file("cut.vti")), ErrorCode::kTruncated,
              {"cut.vti", "ends inside <VTKFile>"});

  std::string deep;
  for (int i = 0; i < 200000; ++i) deep += "<a>";
  writeText(dir.file("deep.vti"), imageFile("0 1 0 1 0 1", "", deep));
  expectError(openVolume(dir.file("deep.vti")), ErrorCode::kCorrupt, {"deep.vti", "XML at byte"});
}

}  // namespace
}  // namespace voxlink::sources::testing
