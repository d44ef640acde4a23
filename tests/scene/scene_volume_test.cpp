// SPDX-License-Identifier: BSD-3-Clause
// A scene's volume given as a dense source with a threshold or transfer function: the scene's
// voxels are the ones `voxlink convert` keeps (same converter), checked on the foot CT.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "convert/converter.h"
#include "format/bricked_volume.h"
#include "format/voxlink_file.h"
#include "pack/open_file.h"
#include "scene/scene_assembly.h"
#include "scene/scene_description.h"
#include "sources/volume_source.h"
#include "tests/support/test_util.h"

namespace voxlink::scene {
namespace {

constexpr const char* kFoot = "ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd";

template <typename T>
std::vector<T> copy(std::span<const T> s) {
  return std::vector<T>(s.begin(), s.end());
}

TEST(SceneVolume, DenseSourceWithThresholdGivesConvertsVoxels) {
  VOXLINK_REQUIRE_DATA(kFoot);
  const std::string foot = ::voxlink::testing::dataPath(kFoot);
  const auto dir = std::filesystem::temp_directory_path() / "voxlink-scene-volume-test";
  std::filesystem::create_directories(dir);
  // The reference: what `voxlink convert foot.nrrd --threshold 60` writes.
  auto source = sources::openVolume(foot, {});
  ASSERT_TRUE(source) << source.message();
  convert::ConvertOptions options;
  options.classification = convert::thresholdClassification({"60"}).value();
  ASSERT_TRUE(convert::convertVolume(**source, options, (dir / "convert.vxl").string()));
  auto reference = pack::openFile((dir / "convert.vxl").string());
  ASSERT_TRUE(reference) << reference.message();

  const std::string json =
      R"({"objects": [{"type": "volume", "file": ")" + foot + R"(", "threshold": 60}]})";
  auto description = parseSceneDescription(json, (dir / "foot.scene.json").string());
  ASSERT_TRUE(description) << description.message();
  auto built = buildScene(*description);
  ASSERT_TRUE(built) << built.message();
  ASSERT_TRUE(format::writeBrickedVolume((dir / "scene.vxl").string(), built->volume));
  auto scene = pack::openFile((dir / "scene.vxl").string());
  ASSERT_TRUE(scene) << scene.message();

  EXPECT_EQ(built->report.volumeVoxels, reference->voxelCount());
  EXPECT_GT(reference->voxelCount(), 1000000u);
  EXPECT_EQ(copy(scene->occupancyWords()), copy(reference->occupancyWords()));
  EXPECT_EQ(copy(scene->rowStarts()), copy(reference->rowStarts()));
  EXPECT_EQ(copy(scene->rowMaskWords()), copy(reference->rowMaskWords()));
  EXPECT_EQ(copy(scene->gradientCodes()), copy(reference->gradientCodes()));
  EXPECT_EQ(0, std::memcmp(scene->valueBytes(), reference->valueBytes(),
                           reference->voxelCount() * storedSize(reference->valueType())));
  std::filesystem::remove_all(dir);
}

TEST(SceneVolume, ThresholdAndTfAreCheckedInTheSceneFile) {
  auto both = parseSceneDescription(
      R"({"objects": [{"type": "volume", "file": "a.nrrd", "threshold": 1, "tf": "t.json"}]})",
      "s.json");
  ASSERT_FALSE(both);
  EXPECT_NE(both.message().find("objects[0]"), std::string::npos) << both.message();
  auto reversed = parseSceneDescription(
      R"({"objects": [{"type": "volume", "file": "a.nrrd", "threshold": [9, 2]}]})", "s.json");
  ASSERT_FALSE(reversed);
  EXPECT_NE(reversed.message().find("objects[0].threshold"), std::string::npos)
      << reversed.message();
  auto ranges = parseSceneDescription(
      R"({"objects": [{"type": "volume", "file": "a.nrrd", "threshold": [[1, 2], [5]]}]})",
      "s.json");
  ASSERT_TRUE(ranges) << ranges.message();
  EXPECT_EQ(ranges->objects[0].thresholds, (std::vector<std::string>{"1,2", "5"}));
}

}  // namespace
}  // namespace voxlink::scene
