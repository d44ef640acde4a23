// SPDX-License-Identifier: BSD-3-Clause
// Every sample scene of docs/effects.md built as a user builds it (at its file's resolution) and
// ray traced at 64x64 through the executable with every effect on: the GL ray tracer against the
// float64 tracer over the same voxel scene, at the 45 dB target, with no ray dropped. The sample
// files read the real meshes and molecules from ../shared/data.
#include <gtest/gtest.h>

#include <string>

#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

double psnrOf(const std::string& out) {
  const size_t at = out.find("PSNR ");
  return at == std::string::npos ? -1.0 : std::stod(out.substr(at + 5));
}

class EffectsSample : public ::testing::TestWithParam<const char*> {};

TEST_P(EffectsSample, GlMatchesTheFloat64Tracer) {
  VOXLINK_REQUIRE_DATA("mesh/c3dtm_stanford-bunny.obj");
  const std::string name = GetParam();
  TempDir dir;
  const std::string scene = std::string(VOXLINK_SAMPLE_SCENES) + "/" + name + ".scene.json";
  const std::string vxl = dir.file(name + ".vxl");
  auto r = runVoxlink({"scene", "build", scene, "-o", vxl});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"render", vxl, "-o", dir.file("fx.png"), "--size", "64x64", "--effects", "all",
                  "--reference"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find(", 0 dropped"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" 0 non-finite"), std::string::npos) << r.out;
  EXPECT_GE(psnrOf(r.out), 45.0) << r.out;
}

INSTANTIATE_TEST_SUITE_P(SampleScenes, EffectsSample,
                         ::testing::Values("cornell-spheres", "bunny-glass", "dragon",
                                           "molecule-glass", "house", "foot-mirror"));

}  // namespace
}  // namespace voxlink::testing
