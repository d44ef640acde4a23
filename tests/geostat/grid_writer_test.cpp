// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/grid_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "sources/volume_source.h"
#include "tests/support/test_util.h"

namespace voxlink::geostat {
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
  sources::OpenOptions o;
  o.dims = info.dims;
  o.type = ScalarType::kF64;
  auto raw = sources::openVolume(dir.file("k.raw"), o);
  ASSERT_TRUE(raw) << raw.message();
  auto all = sources::readAll(**raw);
  ASSERT_TRUE(all);
  EXPECT_EQ(std::memcmp(all->data(), v.data(), 24 * sizeof(double)), 0);
}

// Endings in capitals pick the same formats (FIELD.NPY is a NumPy file to numpy.load).
TEST(GridWriter, EndingsIgnoreCase) {
  testing::TempDir dir;
  const GridFileInfo info{{2, 2, 1}, {0, 0, 0}, {1, 1, 1}, ScalarType::kF32};
  const double slice[4] = {1, 2, 3, 4};
  for (const char* name : {"K.NHDR", "F.Npy"}) {
    auto w = GridWriter::create(dir.file(name), info);
    ASSERT_TRUE(w) << w.message();
    ASSERT_TRUE((*w)->append(1, slice));
    ASSERT_TRUE((*w)->finish());
  }
  EXPECT_EQ(testing::listDir(dir.path()), (std::vector<std::string>{"F.Npy", "K.NHDR", "K.raw"}));
  auto npy = sources::openVolume(dir.file("F.Npy"));
  ASSERT_TRUE(npy) << npy.message();
  EXPECT_EQ((*npy)->info().dims, (std::array<uint32_t, 3>{2, 2, 1}));
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
  EXPECT_NE(st.message().find("4 nodes written, 8 expected"), std::string::npos) << st.message();
}

// Values that are not finite in the file's type are refused, naming the node: 1e308 fits f64
// but is inf as f32; NaN in neither. Nothing is left of the refused grid.
TEST(GridWriter, RefusesValuesThatAreNotFiniteInTheFilesType) {
  testing::TempDir dir;
  const GridFileInfo f32{{2, 2, 2}, {0, 0, 0}, {1, 1, 1}, ScalarType::kF32};
  auto w = GridWriter::create(dir.file("f.nhdr"), f32);
  ASSERT_TRUE(w);
  const double slice[4] = {1, 2, 3, 4}, huge[4] = {1, 2, 1e308, 4};
  ASSERT_TRUE((*w)->append(1, slice));
  auto st = (*w)->append(1, huge);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("f.nhdr: value inf at node (0, 1, 1) is not finite as f32"),
            std::string::npos)
      << st.message();
  const GridFileInfo f64{{2, 2, 1}, {0, 0, 0}, {1, 1, 1}, ScalarType::kF64};
  auto d = GridWriter::create(dir.file("d.npy"), f64);
  ASSERT_TRUE(d);
  ASSERT_TRUE((*d)->append(1, huge));
  const double nan[4] = {1, std::nan(""), 3, 4};
  auto d2 = GridWriter::create(dir.file("d2.npy"), f64);
  ASSERT_TRUE(d2);
  st = (*d2)->append(1, nan);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("at node (1, 0, 0) is not finite as f64"), std::string::npos)
      << st.message();
  w->reset();
  d->reset();
  d2->reset();
  for (const std::string& name : testing::listDir(dir.path()))
    EXPECT_EQ(name.find(".vl-"), std::string::npos) << name;
}

}  // namespace
}  // namespace voxlink::geostat
