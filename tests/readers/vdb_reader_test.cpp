// SPDX-License-Identifier: BSD-3-Clause
// OpenVDB: a float grid built here from the neghip volume (active where the value >= 40, at an
// index offset, with an active tile and an inactive voxel holding a non-background value) must
// read back as the dense box of its active voxels, background elsewhere.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cstring>
#include <map>

#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

using openvdb::Coord;

constexpr float kBackground = -1.0f;
constexpr int kN = 64;
const Coord kOffset(5, -3, 100);
// An 8^3 block aligned to leaf boundaries, inside the data: becomes an active tile.
const openvdb::CoordBBox kTile(Coord(24, 16, 120), Coord(31, 23, 127));
constexpr float kTileValue = 1000.0f;

class VdbReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(dataPath("volume/neghip_64x64x64_uint8.raw")))
      GTEST_SKIP() << "neghip missing";
    openvdb::initialize();
    const auto neghip = readBytes(dataPath("volume/neghip_64x64x64_uint8.raw"));
    ASSERT_EQ(neghip.size(), size_t{kN} * kN * kN);
    auto grid = openvdb::FloatGrid::create(kBackground);
    grid->setName("density");
    auto transform = openvdb::math::Transform::createLinearTransform(0.5);
    transform->postTranslate(openvdb::Vec3d(10, 20, 30));
    grid->setTransform(transform);
    auto acc = grid->getAccessor();
    for (int z = 0; z < kN; ++z)
      for (int y = 0; y < kN; ++y)
        for (int x = 0; x < kN; ++x) {
          const uint8_t v = neghip[(size_t(z) * kN + y) * kN + x];
          if (v < 40) continue;
          const Coord c = Coord(x, y, z) + kOffset;
          acc.setValueOn(c, float(v));
          active_[c] = float(v);
        }
    grid->tree().fill(kTile, kTileValue, true);
    for (auto it = kTile.begin(); it; ++it) active_[*it] = kTileValue;
    // An inactive voxel inside the box that stores something other than the background.
    inactiveInside_ = Coord(20, 20, 120);
    while (active_.count(inactiveInside_)) inactiveInside_.x() += 1;
    ASSERT_LT(inactiveInside_.x(), kN + kOffset.x());
    grid->tree().setValueOff(inactiveInside_, 77.0f);
    ASSERT_FALSE(grid->tree().isValueOn(inactiveInside_));

    auto other = openvdb::Vec3SGrid::create();
    other->setName("velocity");
    other->tree().setValueOn(Coord(0, 0, 0), openvdb::Vec3s(1, 2, 3));
    path_ = dir_.file("neghip.vdb");
    openvdb::io::File(path_).write({other, grid});
  }

  TempDir dir_;
  std::string path_;
  std::map<Coord, float> active_;
  Coord inactiveInside_;
};

TEST_F(VdbReaderTest, ActiveBoxIsDenseWithBackgroundForInactiveVoxels) {
  Coord lo = active_.begin()->first, hi = lo;
  for (const auto& [c, v] : active_) {
    lo = Coord::minComponent(lo, c);
    hi = Coord::maxComponent(hi, c);
  }
  auto source = openOrDie(path_);
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.format, "vdb");
  EXPECT_EQ(info.type, ScalarType::kF32);
  const std::array<uint32_t, 3> dims{static_cast<uint32_t>(hi.x() - lo.x() + 1),
                                     static_cast<uint32_t>(hi.y() - lo.y() + 1),
                                     static_cast<uint32_t>(hi.z() - lo.z() + 1)};
  EXPECT_EQ(info.dims, dims);
  EXPECT_EQ(info.spacing, (std::array<double, 3>{0.5, 0.5, 0.5}));
  EXPECT_EQ(info.origin,
            (std::array<double, 3>{10 + 0.5 * lo.x(), 20 + 0.5 * lo.y(), 30 + 0.5 * lo.z()}));
  EXPECT_TRUE(hasNote(info, cat("grid 'density'"))) << notesOf(info);
  EXPECT_TRUE(hasNote(info, cat("from index (", lo.x(), ",", lo.y(), ",", lo.z(), ")")))
      << notesOf(info);

  std::vector<float> expected(static_cast<size_t>(dims[0]) * dims[1] * dims[2], kBackground);
  for (const auto& [c, v] : active_)
    expected[(size_t(c.z() - lo.z()) * dims[1] + (c.y() - lo.y())) * dims[0] + (c.x() - lo.x())] =
        v;
  for (uint32_t slab : {1u, 5u, 8u, dims[2]}) {
    SCOPED_TRACE(slab);
    const auto data = readInSlabs(*source, slab);
    ASSERT_EQ(data.size(), expected.size() * 4);
    EXPECT_EQ(std::memcmp(data.data(), expected.data(), data.size()), 0);
  }

  // The active flags: exactly the active voxels (the tile's included, not the inactive voxel
  // that stores a value).
  EXPECT_TRUE(source->hasInactiveVoxels());
  std::vector<uint8_t> expectedActive(expected.size(), 0);
  for (const auto& [c, v] : active_)
    expectedActive[(size_t(c.z() - lo.z()) * dims[1] + (c.y() - lo.y())) * dims[0] +
                   (c.x() - lo.x())] = 1;
  std::vector<uint8_t> activeFlags(expected.size(), 7);
  const uint32_t half = dims[2] / 2;
  ASSERT_TRUE(
      source->readActive(half, dims[2] - half, activeFlags.data() + half * dims[0] * dims[1]));
  ASSERT_TRUE(source->readActive(0, half, activeFlags.data()));
  EXPECT_EQ(activeFlags, expectedActive);
  EXPECT_FALSE(source->readActive(1, dims[2], activeFlags.data()));
}

TEST_F(VdbReaderTest, GridSelectionByNameAndRefusals) {
  OpenOptions named;
  named.vdbGrid = "density";
  EXPECT_TRUE(openVolume(path_, named));
  named.vdbGrid = "nothere";
  expectError(openVolume(path_, named), ErrorCode::kInvalidArgument,
              {"neghip.vdb", "nothere", "'density' (float)", "'velocity'"});
  named.vdbGrid = "velocity";
  expectError(openVolume(path_, named), ErrorCode::kUnsupported,
              {"neghip.vdb", "velocity", "vec3s", "float grids"});
}

// Damaged files: every cut and a sweep of flipped bytes over the file give an error or a volume,
// never a crash (OpenVDB throws from its lazily loaded leaves, or corrupts its heap, on some).
TEST_F(VdbReaderTest, DamagedFilesGiveErrorsNotCrashes) {
  const auto whole = readBytes(path_);
  const std::string damaged = dir_.file("damaged.vdb");
  int refused = 0, trials = 0;
  auto attempt = [&](const std::vector<uint8_t>& bytes) {
    writeBytes(damaged, bytes);
    auto source = openVolume(damaged);
    ++trials;
    if (!source) {
      ++refused;
      EXPECT_NE(source.message().find("damaged.vdb"), std::string::npos) << source.message();
      return;
    }
    // Damage may leave a huge active box: read a few slices, which is where lazily loaded
    // leaves used to throw.
    const VolumeInfo& info = (*source)->info();
    if (info.sliceBytes() > (size_t{64} << 20)) return;
    std::vector<uint8_t> slice(info.sliceBytes());
    for (uint32_t z = 0; z < std::min(info.dims[2], 8u); ++z)
      if (!(*source)->read(z, 1, slice.data())) break;
  };
  for (size_t cut : {size_t{100}, whole.size() / 3, whole.size() / 2, whole.size() - 64})
    attempt(std::vector<uint8_t>(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(cut)));
  // (Flips start past the file and grid headers: a flipped metadata length makes OpenVDB
  // allocate gigabytes before it fails, ~17 s here; fine for a user, too slow for the suite.)
  for (size_t at = 1000; at < whole.size(); at += whole.size() / 23) {
    auto bytes = whole;
    for (size_t k = 0; k < 16 && at + k < bytes.size(); ++k) bytes[at + k] ^= 0xA5;
    attempt(bytes);
  }
  EXPECT_GT(refused, trials / 3);
}

}  // namespace
}  // namespace voxlink::sources::testing
