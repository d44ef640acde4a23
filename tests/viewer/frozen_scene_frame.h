// SPDX-License-Identifier: BSD-3-Clause
// The frame a dynamic scene must match: the scene frozen at time t, built by the exact CPU path
// (scene::buildScene) into a static file and drawn by VoxLinkRenderer. `draw` renders it with the
// caller's camera and settings; build or open failures fail the test and give an empty image.
#pragma once

#include <gtest/gtest.h>

#include <functional>

#include "format/bricked_volume.h"
#include "format/voxlink_file.h"
#include "render/gl/voxlink_renderer.h"
#include "render/image.h"
#include "scene/scene_assembly.h"
#include "tests/support/test_util.h"
#include "viewer/dynamic_scene.h"

namespace voxlink::viewer::testing {

inline render::Image frozenSceneFrame(
    const DynamicScene& dynamic, double t, const ::voxlink::testing::TempDir& dir,
    const std::function<render::Image(render::gl::VolumeRenderer&)>& draw) {
  auto built = scene::buildScene(dynamic.frozenAt(t));
  EXPECT_TRUE(built) << built.message();
  if (!built) return {};
  EXPECT_TRUE(format::writeBrickedVolume(dir.file("frozen.vxl"), built->volume).isOk());
  auto file = format::VoxLinkFile::open(dir.file("frozen.vxl"));
  EXPECT_TRUE(file) << file.message();
  if (!file) return {};
  auto host = render::gl::VoxLinkRenderer::create(*file);
  EXPECT_TRUE(host) << host.message();
  return host ? draw(**host) : render::Image{};
}

}  // namespace voxlink::viewer::testing
