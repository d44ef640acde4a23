// SPDX-License-Identifier: BSD-3-Clause
// Re-classification from the source a file records: a TF that asks for removed values is
// noticed, the background job re-converts the tooth CT keeping what the TF shows, and the new
// file holds what the TF asks for.
#include "viewer/app/detail/reclassifier.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "pack/open_file.h"
#include "tests/support/test_util.h"
#include "tests/viewer/volume_fixtures.h"
#include "viewer/app/detail/classification_check.h"

namespace voxlink::viewer {

using render::DenseVolume;

namespace {

TEST(Reclassifier, ReconvertsTheRecordedSourceWithTheNewTf) {
  VOXLINK_REQUIRE_DATA("ct/tooth_103x94x161_uint8.raw");
  voxlink::testing::TempDir dir;
  auto file = render::testing::convertWithThreshold(render::testing::toothPath(),
                                                    render::testing::toothOpenOptions(), "150",
                                                    dir.file("tooth.vxl"));
  ASSERT_TRUE(file) << file.message();
  const FileClassification before = fileClassification(*file);
  ASSERT_TRUE(before.recorded);
  tf::TransferFunction tf;
  tf.opacity = {{119.5, 0.0}, {140, 0.2}, {255, 0.8}};
  tf.color = {{0, {1, 1, 1}}};
  const auto missing = visibleButRemoved(tf, before);
  ASSERT_EQ(missing.size(), 1u);
  EXPECT_EQ(missing[0].lo, 119.5);
  EXPECT_EQ(missing[0].hi, 150);

  Reclassifier job;
  const std::string out = Reclassifier::outputPathFor(file->path());
  EXPECT_EQ(out, dir.file("tooth.reclassified.vxl"));
  EXPECT_EQ(Reclassifier::outputPathFor(out), out);
  ASSERT_TRUE(job.start(*file, tf, out).isOk());
  for (int i = 0; i < 6000 && job.running(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  auto result = job.takeResult();
  ASSERT_TRUE(result.has_value());
  ASSERT_TRUE(*result) << result->message();
  auto reloaded = pack::openFile(result->value());
  ASSERT_TRUE(reloaded) << reloaded.message();
  EXPECT_GT(reloaded->voxelCount(), file->voxelCount());
  EXPECT_GE(reloaded->header().valueMin, 120.0);
  EXPECT_TRUE(visibleButRemoved(tf, fileClassification(*reloaded)).empty());
  EXPECT_FALSE(job.takeResult().has_value());
}

TEST(Reclassifier, RefusesFilesWithoutARecordedSource) {
  const DenseVolume dense =
      render::testing::makeVolume({8, 8, 8}, {1, 1, 1}, [](int x, int, int) { return x; });
  auto sparse = render::testing::sparsify(dense, [](double v) { return v > 3; }, {});
  ASSERT_TRUE(sparse);
  voxlink::testing::TempDir dir;
  auto file = render::testing::writeAndOpen(*sparse, dir.file("bare.vxl"));
  ASSERT_TRUE(file);
  Reclassifier job;
  tf::TransferFunction tf;
  tf.opacity = {{0, 1.0}};
  EXPECT_FALSE(job.start(*file, tf, dir.file("out.vxl")));
  EXPECT_FALSE(job.running());
}

}  // namespace
}  // namespace voxlink::viewer
