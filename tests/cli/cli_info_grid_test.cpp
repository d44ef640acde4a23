// SPDX-License-Identifier: BSD-3-Clause
// `voxlink info` says where the grid is: origin, spacing, world bounds, slicing axis and brick
// grid, in the text report and in --json, for a converted CT and for a scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "format/voxlink_file.h"
#include "pack/open_file.h"
#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

std::array<double, 3> triple(const nlohmann::json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

TEST(CliInfoGrid, HeadsqSpacingBoundsAxisAndBricks) {
  TempDir dir;
  const std::string vxl = dir.file("headsq.vxl");
  // headsq: 64 x 64 x 93 voxels of 3.2 x 3.2 x 1.5 mm, no origin in the header (samples/headsq).
  auto r = runVoxlink({"convert", std::string(VOXLINK_SAMPLES_DIR) + "/headsq/headsq.nrrd",
                       "--threshold", "1400", "--axis", "x", "--brick", "16", "-o", vxl, "-q"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"info", vxl, "--json", "--no-vdb"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(triple(j["origin"]), (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(triple(j["spacing"]), (std::array<double, 3>{3.2, 3.2, 1.5}));
  const auto lo = triple(j["world_bounds"]["min"]);
  const auto hi = triple(j["world_bounds"]["max"]);
  const std::array<double, 3> wantLo{-1.6, -1.6, -0.75}, wantHi{203.2, 203.2, 138.75};
  for (int a = 0; a < 3; ++a) {
    EXPECT_DOUBLE_EQ(lo[a], wantLo[a]) << a;
    EXPECT_DOUBLE_EQ(hi[a], wantHi[a]) << a;
  }
  EXPECT_EQ(j["axis"], "x");
  EXPECT_EQ(j["brick_size"], 16);
  EXPECT_EQ(j["brick_grid"], nlohmann::json({4, 4, 6}));  // ceil(64/16), ceil(64/16), ceil(93/16)
  EXPECT_EQ(j["dims"], nlohmann::json({64, 64, 93}));     // the keys that were there stay
  r = runVoxlink({"info", vxl, "--no-vdb"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("grid: origin (0, 0, 0), spacing (3.2, 3.2, 1.5); world bounds (-1.6, "
                       "-1.6, -0.75) to (203.2, 203.2, 138.75)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("rows along x, bricks of 16^3 voxels, 4x4x6 bricks"), std::string::npos)
      << r.out;
}

TEST(CliInfoGrid, SceneBoundsHoldItsObjectsAndMatchTheHeader) {
  TempDir dir;
  const std::string vxl = dir.file("house.vxl");
  auto r =
      runVoxlink({"scene", "build", std::string(VOXLINK_SAMPLES_DIR) + "/scenes/house.scene.json",
                  "--resolution", "48", "-o", vxl, "-q"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"info", vxl, "--json", "--no-vdb"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  auto file = pack::openFile(vxl);
  ASSERT_TRUE(file) << file.message();
  const format::FileHeader& h = file->header();
  const auto origin = triple(j["origin"]), spacing = triple(j["spacing"]);
  const auto lo = triple(j["world_bounds"]["min"]), hi = triple(j["world_bounds"]["max"]);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(origin[a], h.origin[a]);
    EXPECT_EQ(spacing[a], h.spacing[a]);
    EXPECT_NEAR(hi[a] - lo[a], h.dims[a] * h.spacing[a], 1e-9 * h.dims[a] * h.spacing[a]);
    EXPECT_EQ(j["brick_grid"][a], h.brickGrid[a]);
  }
  EXPECT_EQ(std::max({h.dims[0], h.dims[1], h.dims[2]}), 48u);
  // The brass sphere of house.scene.json: centre (0, 0.4, 0), radius 0.35, lies inside.
  const std::array<double, 3> centre{0.0, 0.4, 0.0};
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(lo[a], centre[a] - 0.35) << a;
    EXPECT_GE(hi[a], centre[a] + 0.35) << a;
  }
  EXPECT_EQ(j["axis"], "z");
  EXPECT_EQ(j["brick_size"], 8);
  EXPECT_TRUE(j.contains("scene"));
}

}  // namespace
}  // namespace voxlink::testing
