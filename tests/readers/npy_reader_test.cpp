// SPDX-License-Identifier: BSD-3-Clause
// Every .npy variant the reader accepts, written here per the specification, must load as
// the same volume: logical a[z][y][x] = 100 z + 10 y + x (mod the type's range).
#include "sources/readers/npy_reader.h"

#include <gtest/gtest.h>

#include "geostat/grid_writer.h"
#include "sources/volume_source.h"
#include "tests/readers/npy_test_util.h"
#include "tests/support/test_util.h"

namespace voxlink::sources {

namespace {

using testing::appendValue;
using testing::npyBytes;

constexpr uint32_t kNx = 5, kNy = 4, kNz = 3;

double expected(uint32_t x, uint32_t y, uint32_t z) { return 100.0 * z + 10.0 * y + x; }

template <class T>
std::vector<uint8_t> arrayData(bool fortran, bool bigEndian, int shift) {
  std::vector<uint8_t> out;
  if (!fortran) {
    for (uint32_t z = 0; z < kNz; ++z)
      for (uint32_t y = 0; y < kNy; ++y)
        for (uint32_t x = 0; x < kNx; ++x)
          appendValue<T>(out, static_cast<T>(expected(x, y, z) - shift), bigEndian);
  } else {  // first index (z) fastest
    for (uint32_t x = 0; x < kNx; ++x)
      for (uint32_t y = 0; y < kNy; ++y)
        for (uint32_t z = 0; z < kNz; ++z)
          appendValue<T>(out, static_cast<T>(expected(x, y, z) - shift), bigEndian);
  }
  return out;
}

template <class T>
void checkVariant(const std::string& code, ScalarType type, int major, bool fortran,
                  bool bigEndian) {
  testing::TempDir dir;
  const int shift = std::is_signed_v<T> && sizeof(T) == 1 ? 128 : 0;  // i1 holds -128..127
  const char order = sizeof(T) == 1 ? '|' : bigEndian ? '>' : '<';
  const std::string dict =
      cat("{'descr': '", order, code, "', 'fortran_order': ", fortran ? "True" : "False",
          ", 'shape': (", kNz, ", ", kNy, ", ", kNx, "), }");
  const std::string path = dir.file("a.npy");
  testing::writeBytes(path, npyBytes(major, dict, arrayData<T>(fortran, bigEndian, shift)));
  const std::string what = cat(code, " v", major, fortran ? " F" : " C", bigEndian ? " BE" : " LE");
  auto source = openVolume(path);
  ASSERT_TRUE(source) << what << ": " << source.message();
  const VolumeInfo& info = (*source)->info();
  EXPECT_EQ(info.format, "npy");
  EXPECT_EQ(info.type, type) << what;
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{kNx, kNy, kNz})) << what;
  auto all = readAll(**source);
  ASSERT_TRUE(all) << all.message();
  const T* v = reinterpret_cast<const T*>(all->data());
  for (uint32_t z = 0; z < kNz; ++z)
    for (uint32_t y = 0; y < kNy; ++y)
      for (uint32_t x = 0; x < kNx; ++x)
        ASSERT_EQ(v[(z * kNy + y) * kNx + x], static_cast<T>(expected(x, y, z) - shift))
            << what << " at " << x << "," << y << "," << z;
  // Reading one middle slice alone gives the same values.
  std::vector<T> slice(kNx * kNy);
  ASSERT_TRUE((*source)->read(1, 1, slice.data()));
  EXPECT_EQ(slice[kNx + 2], static_cast<T>(expected(2, 1, 1) - shift)) << what;
  // C order in native byte order is served zero-copy from the mapping.
  const bool zeroCopy = !fortran && (!bigEndian || sizeof(T) == 1);
  EXPECT_EQ((*source)->map(0, kNz) != nullptr, zeroCopy) << what;
}

TEST(NpyReader, ReadsEveryDtypeVersionOrderAndByteOrder) {
  for (int major : {1, 2, 3})
    for (bool fortran : {false, true})
      for (bool big : {false, true}) {
        checkVariant<uint8_t>("u1", ScalarType::kU8, major, fortran, big);
        checkVariant<int8_t>("i1", ScalarType::kI8, major, fortran, big);
        checkVariant<uint16_t>("u2", ScalarType::kU16, major, fortran, big);
        checkVariant<int16_t>("i2", ScalarType::kI16, major, fortran, big);
        checkVariant<uint32_t>("u4", ScalarType::kU32, major, fortran, big);
        checkVariant<int32_t>("i4", ScalarType::kI32, major, fortran, big);
        checkVariant<float>("f4", ScalarType::kF32, major, fortran, big);
        checkVariant<double>("f8", ScalarType::kF64, major, fortran, big);
      }
}

TEST(NpyReader, TwoDimensionalAndOneDimensionalShapes) {
  testing::TempDir dir;
  std::vector<uint8_t> data;
  for (int i = 0; i < 6; ++i) appendValue<uint16_t>(data, static_cast<uint16_t>(i), false);
  // (2, 3) in Fortran order: a[r][c] at r + 2 c, so the bytes 0..5 are a = [[0, 2, 4], [1, 3, 5]].
  testing::writeBytes(
      dir.file("f.npy"),
      npyBytes(1, "{'descr': '<u2', 'fortran_order': True, 'shape': (2, 3), }", data));
  auto f = openVolume(dir.file("f.npy"));
  ASSERT_TRUE(f) << f.message();
  EXPECT_EQ((*f)->info().dims, (std::array<uint32_t, 3>{3, 2, 1}));
  auto all = readAll(**f);
  ASSERT_TRUE(all);
  const auto* v = reinterpret_cast<const uint16_t*>(all->data());
  EXPECT_EQ(std::vector<uint16_t>(v, v + 6), (std::vector<uint16_t>{0, 2, 4, 1, 3, 5}));
  // 1-D, Python 2 long literal, leading axes of size 1, unaligned header: all accepted.
  testing::writeBytes(
      dir.file("l.npy"),
      npyBytes(1, "{'descr': '<u2', 'fortran_order': False, 'shape': (1L, 1, 6L), }", data, 16));
  auto l = openVolume(dir.file("l.npy"));
  ASSERT_TRUE(l) << l.message();
  EXPECT_EQ((*l)->info().dims, (std::array<uint32_t, 3>{6, 1, 1}));
  testing::writeBytes(
      dir.file("o.npy"),
      npyBytes(2, "{\"shape\": (6,), \"fortran_order\": False, \"descr\": \"<u2\"}", data));
  auto o = openVolume(dir.file("o.npy"));
  ASSERT_TRUE(o) << o.message();
  EXPECT_EQ((*o)->info().dims, (std::array<uint32_t, 3>{6, 1, 1}));
}

TEST(NpyReader, BadInputNamesTheFileAndTheField) {
  testing::TempDir dir;
  std::vector<uint8_t> data(24, 0);
  struct Case {
    std::string name, dict;
    std::vector<uint8_t> bytes;
    ErrorCode code;
    std::string mentions;
  };
  const std::string good = "{'descr': '<f8', 'fortran_order': False, 'shape': (3,), }";
  std::vector<Case> cases = {
      {"dtype.npy",
       "{'descr': '<i8', 'fortran_order': False, 'shape': (3,), }",
       {},
       ErrorCode::kUnsupported,
       "'descr': '<i8'"},
      {"complex.npy",
       "{'descr': '<c16', 'fortran_order': False, 'shape': (3,), }",
       {},
       ErrorCode::kUnsupported,
       "'descr'"},
      {"struct.npy",
       "{'descr': [('a', '<f4')], 'fortran_order': False, 'shape': (3,), }",
       {},
       ErrorCode::kCorrupt,
       "structured"},
      {"order.npy",
       "{'descr': '<f8', 'fortran_order': 0, 'shape': (3,), }",
       {},
       ErrorCode::kCorrupt,
       "'fortran_order'"},
      {"shape.npy",
       "{'descr': '<f8', 'fortran_order': False, 'shape': [3], }",
       {},
       ErrorCode::kCorrupt,
       "'shape'"},
      {"neg.npy",
       "{'descr': '<f8', 'fortran_order': False, 'shape': (-3,), }",
       {},
       ErrorCode::kCorrupt,
       "'shape'"},
      {"key.npy",
       "{'descr': '<f8', 'fortran_order': False, 'shape': (3,), 'extra': 1}",
       {},
       ErrorCode::kCorrupt,
       "'extra'"},
      {"missing.npy",
       "{'descr': '<f8', 'shape': (3,), }",
       {},
       ErrorCode::kCorrupt,
       "'fortran_order': missing"},
      {"scalar.npy",
       "{'descr': '<f8', 'fortran_order': False, 'shape': (), }",
       {},
       ErrorCode::kUnsupported,
       "scalar"},
      {"4d.npy",
       "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3, 1, 1), }",
       {},
       ErrorCode::kUnsupported,
       "'shape'"},
      {"zero.npy",
       "{'descr': '<f8', 'fortran_order': False, 'shape': (0,), }",
       {},
       ErrorCode::kInvalidArgument,
       "'shape'"},
      {"nobyteorder.npy",
       "{'descr': '|f8', 'fortran_order': False, 'shape': (3,), }",
       {},
       ErrorCode::kUnsupported,
       "byte order"},
  };
  for (Case& c : cases) c.bytes = npyBytes(1, c.dict, data);
  std::vector<uint8_t> truncated = npyBytes(1, good, data);
  truncated.resize(truncated.size() - 5);
  cases.push_back({"truncated.npy", "", truncated, ErrorCode::kTruncated, "npy data"});
  std::vector<uint8_t> trailing = npyBytes(1, good, data);
  trailing.push_back(0);
  cases.push_back({"trailing.npy", "", trailing, ErrorCode::kSizeMismatch, "trailing"});
  std::vector<uint8_t> shortHeader = npyBytes(1, good, data);
  shortHeader.resize(40);
  cases.push_back({"header.npy", "", shortHeader, ErrorCode::kTruncated, "header length"});
  std::vector<uint8_t> version = npyBytes(1, good, data);
  version[6] = 4;
  cases.push_back({"version.npy", "", version, ErrorCode::kUnsupported, "version: 4.0"});
  std::vector<uint8_t> noNewline = npyBytes(1, good, data);
  noNewline[npyBytes(1, good, {}).size() - 1] = ' ';
  cases.push_back({"newline.npy", "", noNewline, ErrorCode::kCorrupt, "newline"});
  for (const Case& c : cases) {
    const std::string path = dir.file(c.name);
    testing::writeBytes(path, c.bytes);
    auto r = openNpy(path, {});
    ASSERT_FALSE(r) << c.name;
    EXPECT_EQ(r.code(), c.code) << c.name << ": " << r.message();
    EXPECT_NE(r.message().find(path), std::string::npos) << r.message();
    EXPECT_NE(r.message().find(c.mentions), std::string::npos) << c.name << ": " << r.message();
  }
}

TEST(NpyReader, OptionsMustAgreeWithTheHeader) {
  testing::TempDir dir;
  std::vector<uint8_t> data(24, 0);
  testing::writeBytes(
      dir.file("a.npy"),
      npyBytes(1, "{'descr': '<f8', 'fortran_order': False, 'shape': (3,), }", data));
  OpenOptions o;
  o.dims = std::array<uint32_t, 3>{4, 1, 1};
  auto r = openVolume(dir.file("a.npy"), o);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.code(), ErrorCode::kSizeMismatch);
  EXPECT_NE(r.message().find("--dims"), std::string::npos);
}

TEST(NpyReader, ReadsWhatTheKrigeCommandWrites) {
  testing::TempDir dir;
  geostat::GridFileInfo info{{3, 2, 2}, {0, 0, 0}, {1, 1, 1}, ScalarType::kF32};
  auto w = geostat::GridWriter::create(dir.file("g.npy"), info);
  ASSERT_TRUE(w) << w.message();
  std::vector<double> values(12);
  for (int i = 0; i < 12; ++i) values[i] = i * 0.5;
  ASSERT_TRUE((*w)->append(1, values.data()));
  ASSERT_TRUE((*w)->append(1, values.data() + 6));
  ASSERT_TRUE((*w)->finish());
  auto s = openVolume(dir.file("g.npy"));
  ASSERT_TRUE(s) << s.message();
  EXPECT_EQ((*s)->info().dims, info.dims);
  auto all = readAll(**s);
  ASSERT_TRUE(all);
  const auto* f = reinterpret_cast<const float*>(all->data());
  for (int i = 0; i < 12; ++i) EXPECT_EQ(f[i], float(i * 0.5));
  EXPECT_EQ(geostat::npyHeader(ScalarType::kF64, {3, 2, 2}).size() % 64, 0u);
}

}  // namespace
}  // namespace voxlink::sources
