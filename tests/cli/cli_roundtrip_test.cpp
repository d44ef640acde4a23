// SPDX-License-Identifier: BSD-3-Clause
// The main job through the command line: convert, info (text and JSON), validate.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

TEST(CliRoundTrip, ConvertInfoValidateOnTheTooth) {
  VOXLINK_REQUIRE_DATA("ct/tooth_103x94x161_uint8.raw");
  TempDir dir;
  const std::string out = dir.file("tooth.vxl");
  auto r = runVoxlink({"convert", dataPath("ct/tooth_103x94x161_uint8.raw"), "--dims", "103,94,161",
                       "--type", "u8", "--threshold", "90", "-o", out});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("tooth.vxl: "), std::string::npos);
  EXPECT_NE(r.out.find("B/voxel"), std::string::npos);
  EXPECT_NE(r.out.find("gradients polar16, error mean"), std::string::npos);
  r = runVoxlink({"validate", out});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find(": ok"), std::string::npos);
  r = runVoxlink({"info", "--json", out});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"voxels", "occupancy", "bricks_nonempty_fraction", "bytes_total",
                          "bytes_per_voxel", "sections"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_GT(j["voxels"].get<uint64_t>(), 0u);
  EXPECT_EQ(j["bytes_total"].get<uint64_t>(), std::filesystem::file_size(out));
  EXPECT_EQ(j["peer"]["name"], "OpenVDB FloatGrid");
  EXPECT_GT(j["peer"]["bytes"].get<uint64_t>(), 0u);
  r = runVoxlink({"info", out});
  ASSERT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("resolution [brick]"), std::string::npos);
  EXPECT_NE(r.out.find("103x94x161 [8]"), std::string::npos);
}

}  // namespace
}  // namespace voxlink::testing
