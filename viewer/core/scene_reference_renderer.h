// The float64 reference for scenes (format version 2): the same voxel scene, camera, transfer
// function and shading model as the GL ray tracer's voxel sampling (shaders/voxlink_scene*.glsl
// and, with effects, voxlink_effects.glsl), evaluated in double precision straight from the
// file: EffectsTracer over a VoxelSceneWalker. It measures the GL implementation; what
// voxelization itself costs is measured against the original geometry (an exact SceneWalker).
#pragma once

#include <array>

#include "format/transfer_function.h"
#include "format/voxlink_file.h"
#include "viewer/core/camera.h"
#include "viewer/core/effects_tracer.h"
#include "viewer/core/image.h"
#include "viewer/core/render_settings.h"
#include "viewer/core/voxel_scene_walker.h"

namespace voxlink::viewer {

class SceneReferenceRenderer {
 public:
  // Both must outlive the renderer. Works for version 1 files too (every voxel a volume sample).
  SceneReferenceRenderer(const format::VoxLinkFile& file, const format::TransferFunction& tf)
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

}  // namespace voxlink::viewer
