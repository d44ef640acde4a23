// SPDX-License-Identifier: BSD-3-Clause
// GSLIB / GEO-EAS grids: the real SGeMS exports (zipped) and files written here.
#include "sources/readers/gslib_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "sources/volume_source.h"
#include "tests/support/test_util.h"

namespace voxlink::sources {

namespace {

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(GslibReader, ReadsTheZippedMaulesCreekFaciesGrid) {
  VOXLINK_REQUIRE_DATA("geostat/vtk_Maules_Creek_3D.SGEMS.zip");
  const std::string path = testing::dataPath("geostat/vtk_Maules_Creek_3D.SGEMS.zip");
  auto s = openVolume(path);
  ASSERT_TRUE(s) << s.message();
  const VolumeInfo& info = (*s)->info();
  EXPECT_EQ(info.format, "gslib");
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{340, 200, 80}));  // from the title line
  EXPECT_EQ(info.type, ScalarType::kF64);
  // Facies are 0 or 1; the first data rows of the file are 1 1 1 1 1 1 1 1 0 0 1.
  std::vector<double> slice(info.sliceVoxels());
  ASSERT_TRUE((*s)->read(0, 1, slice.data()));
  EXPECT_EQ(std::vector<double>(slice.begin(), slice.begin() + 9),
            (std::vector<double>{1, 1, 1, 1, 1, 1, 1, 1, 0}));
  uint64_t ones = 0;
  for (uint32_t z = 1; z < info.dims[2]; ++z) {  // sequential reads through the archive
    ASSERT_TRUE((*s)->read(z, 1, slice.data()));
    for (double v : slice) {
      ASSERT_TRUE(v == 0 || v == 1);
      ones += v == 1;
    }
  }
  EXPECT_GT(ones, 0u);
  // Reading an earlier slice again rewinds the stream and gives the same values.
  ASSERT_TRUE((*s)->read(0, 1, slice.data()));
  EXPECT_EQ(slice[8], 0.0);
  EXPECT_EQ(slice[10], 1.0);
}

TEST(GslibReader, ReadsTheContinuousTrainingImage) {
  VOXLINK_REQUIRE_DATA("geostat/vtk_TI_horizons_continuous.SGEMS.zip");
  auto s = openVolume(testing::dataPath("geostat/vtk_TI_horizons_continuous.SGEMS.zip"));
  ASSERT_TRUE(s) << s.message();
  EXPECT_EQ((*s)->info().dims, (std::array<uint32_t, 3>{40, 40, 40}));
  auto all = readAll(**s);
  ASSERT_TRUE(all);
  const auto* v = reinterpret_cast<const double*>(all->data());
  EXPECT_DOUBLE_EQ(v[0], -3.853169);  // first data row of the file
  EXPECT_DOUBLE_EQ(v[1], -3.973775);
  for (uint64_t i = 0; i < 64000; ++i) ASSERT_TRUE(std::isfinite(v[i]));
}

TEST(GslibReader, RefusesThePointSetAndSuggestsKriging) {
  VOXLINK_REQUIRE_DATA("geostat/vtk_b_100sampledatawl.sgems");
  const std::string path = testing::dataPath("geostat/vtk_b_100sampledatawl.sgems");
  auto s = openVolume(path);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.code(), ErrorCode::kUnsupported);
  EXPECT_NE(s.message().find("point set"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("voxlink krige"), std::string::npos) << s.message();
}

TEST(GslibReader, DimsFromOptionsAndVariableSelection) {
  testing::TempDir dir;
  const std::string path = dir.file("grid.gslib");
  writeText(path,
            "SGSIM realizations\r\n2\r\nporosity\r\nperm\r\n1 10\r\n2 20\r\n\r\n3 30\r\n4 40\r\n5 "
            "50\r\n6 60\r\n");
  auto noDims = openVolume(path);
  ASSERT_FALSE(noDims);
  EXPECT_EQ(noDims.code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(noDims.message().find("--dims"), std::string::npos) << noDims.message();
  OpenOptions o;
  o.dims = std::array<uint32_t, 3>{3, 2, 1};
  o.variable = "PERM";
  auto s = openVolume(path, o);
  ASSERT_TRUE(s) << s.message();
  auto all = readAll(**s);
  ASSERT_TRUE(all);
  const auto* v = reinterpret_cast<const double*>(all->data());
  EXPECT_EQ(std::vector<double>(v, v + 6), (std::vector<double>{10, 20, 30, 40, 50, 60}));
  o.variable.clear();
  auto first = openVolume(path, o);
  ASSERT_TRUE(first);
  ASSERT_EQ((*first)->info().notes.size(), 1u);
  EXPECT_NE((*first)->info().notes[0].find("porosity"), std::string::npos);
  o.variable = "density";
  auto missing = openVolume(path, o);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.message().find("'density' not found"), std::string::npos) << missing.message();
}

TEST(GslibReader, BadInputNamesTheFileAndTheField) {
  testing::TempDir dir;
  struct Case {
    std::string name, text;
    ErrorCode code;
    std::string mentions;
  };
  const Case cases[] = {
      {"short.sgems", "2 2 1\n1\nv\n1\n2\n3\n", ErrorCode::kTruncated, "3 rows"},
      {"long.sgems", "2 1 1\n1\nv\n1\n2\n3\n", ErrorCode::kSizeMismatch, "3 rows"},
      {"count.sgems", "2 1 1\nthree\nv\n1\n2\n", ErrorCode::kCorrupt, "number of variables"},
      {"names.sgems", "2 1 1\n3\nv\n", ErrorCode::kTruncated, "variable names"},
      {"binary.sgems", std::string("\xb2\x11\x17\x5d\0\0\0\x0bPoint_set", 17),
       ErrorCode::kUnsupported, "binary"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.file(c.name);
    writeText(path, c.text);
    auto r = openVolume(path);
    ASSERT_FALSE(r) << c.name;
    EXPECT_EQ(r.code(), c.code) << c.name << ": " << r.message();
    EXPECT_NE(r.message().find(path), std::string::npos) << r.message();
    EXPECT_NE(r.message().find(c.mentions), std::string::npos) << c.name << ": " << r.message();
  }
  // A bad number is found when its slice is read.
  const std::string bad = dir.file("value.sgems");
  writeText(bad, "2 1 1\n1\nv\n1\nx2\n");
  auto s = openVolume(bad);
  ASSERT_TRUE(s) << s.message();
  std::vector<double> slice(2);
  auto st = (*s)->read(0, 1, slice.data());
  ASSERT_FALSE(st);
  EXPECT_EQ(st.code(), ErrorCode::kCorrupt);
  EXPECT_NE(st.message().find("line 5"), std::string::npos) << st.message();
  EXPECT_NE(st.message().find("'x2'"), std::string::npos) << st.message();
  // Options that disagree with the title.
  OpenOptions o;
  o.dims = std::array<uint32_t, 3>{1, 2, 1};
  auto mismatch = openVolume(bad, o);
  ASSERT_FALSE(mismatch);
  EXPECT_EQ(mismatch.code(), ErrorCode::kSizeMismatch);
  // Every row holds every variable: one value short (or one too many) in a two-variable file
  // was read as long as the selected column was there.
  for (const char* row : {"3", "3 3 3"}) {
    const std::string ragged = dir.file("ragged.sgems");
    writeText(ragged, std::string("2 2 1\n2\nv\nw\n1 1\n2 2\n") + row + "\n4 4\n");
    auto r = openVolume(ragged);
    ASSERT_TRUE(r) << r.message();
    std::vector<double> values(4);
    const Status read = (*r)->read(0, 1, values.data());
    ASSERT_FALSE(read) << row;
    EXPECT_EQ(read.code(), ErrorCode::kCorrupt);
    EXPECT_NE(read.message().find("line 7: "), std::string::npos) << read.message();
    EXPECT_NE(read.message().find("values, the header declares 2 variables"), std::string::npos)
        << read.message();
  }
}

}  // namespace
}  // namespace voxlink::sources
