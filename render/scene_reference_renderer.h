// SPDX-License-Identifier: BSD-3-Clause
// The float64 reference for scenes (format version 2): the same voxel scene, camera, transfer
// function and shading model as the GL ray tracer's voxel sampling (shaders/voxlink_scene*.glsl
// and, with effects, voxlink_effects.glsl), evaluated in double precision straight from the
// file: EffectsTracer over a VoxelSceneWalker. It measures the GL implementation; what
// voxelization itself costs is measured against the original geometry (an exact SceneWalker).
#pragma once

#include <array>

#include "format/voxlink_file.h"
#include "render/camera.h"
#include "render/effects_tracer.h"
#include "render/image.h"
#include "render/render_settings.h"
#include "render/voxel_scene_walker.h"
#include "tf/transfer_function.h"

namespace voxlink::render {

class SceneReferenceRenderer {
 public:
  // Both must outlive the renderer. Works for version 1 files too (every voxel a volume sample).
  SceneReferenceRenderer(const format::VoxLinkFile& file, const tf::TransferFunction& tf)
      : walker_(file), tracer_(walker_, tf) {}

  // Voxel sampling only, as the GL renderer draws scenes; rows in parallel.
  Image render(const Camera& camera, const RenderSettings& settings) const {
    return tracer_.render(camera, settings);
  }
  std::array<double, 4> traceRay(const Ray& ray, const Camera& camera,
                                 const RenderSettings& settings) const {
    return tracer_.traceRay(ray, camera, settings);
  }

 private:
  VoxelSceneWalker walker_;  // before tracer_, which refers to it
  EffectsTracer tracer_;
};

}  // namespace voxlink::render
