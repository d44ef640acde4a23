#include "geostat/grid_writer.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "sources/volume_source.h"
#include "tests/support/test_util.h"

namespace voxlink::kriging {
namespace {

TEST(GridWriter, WritesRawDataWithADetachedNrrdHeader) {
  testing::TempDir dir;
  GridFileInfo info{{4, 3, 2}, {512345.678901, 4.25e6, -7}, {0.5, 2, 1}, ScalarType::kF64};
  auto w = GridWriter::create(dir.file("k.nhdr"), info);
  ASSERT_TRUE(w) << w.message();
  std::vector<double> v(24);
  for (int i = 0; i < 24; ++i) v[i] = i * 1.25;
  ASSERT_TRUE((*w)->append(2, v.data()));
  ASSERT_TRUE((*w)->finish());
  EXPECT_EQ(testing::listDir(dir.path()), (std::vector<std::string>{"k.nhdr", "k.raw"}));
  std::stringstream header;
  header << std::ifstream(dir.file("k.nhdr")).rdbuf();
  EXPECT_NE(header.str().find("sizes: 4 3 2\n"), std::string::npos) << header.str();
  EXPECT_NE(header.str().find("type: double\n"), std::string::npos);
  EXPECT_NE(header.str().find("space origin: (512345.678901,4250000,-7)\n"), std::string::npos)
      << header.str();
  EXPECT_NE(header.str().find("data file: k.raw\n"), std::string::npos);
  convert::OpenOptions o;
  o.dims = info.dims;
  o.type = ScalarType::kF64;
  auto raw = convert::openVolume(dir.file("k.raw"), o);
  ASSERT_TRUE(raw) << raw.message();
  auto all = convert::readAll(**raw);
  ASSERT_TRUE(all);
  EXPECT_EQ(std::memcmp(all->data(), v.data(), 24 * sizeof(double)), 0);
}

TEST(GridWriter, RefusesUnknownEndingsAndIncompleteGrids) {
  testing::TempDir dir;
  auto bad = GridWriter::create(dir.file("k.tif"), {});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.message().find(".nhdr"), std::string::npos);
  auto w =
      GridWriter::create(dir.file("k.npy"), {{2, 2, 2}, {0, 0, 0}, {1, 1, 1}, ScalarType::kF64});
  ASSERT_TRUE(w);
  const double slice[4] = {1, 2, 3, 4};
  ASSERT_TRUE((*w)->append(1, slice));
  auto st = (*w)->finish();
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("1 slices written, 2 expected"), std::string::npos) << st.message();
}

}  // namespace
}  // namespace voxlink::kriging
