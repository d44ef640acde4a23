// SPDX-License-Identifier: BSD-3-Clause
// The float64 ray tracer of the ray-traced scene mode (paper, section 5.2): primary rays
// composited front to back as in the plain scene renderer, and at every surface hit the
// reflected and refracted rays spawned with their share of the ray's weight (opacity transport,
// light_transport.h), shadow rays towards every light. It runs over a SceneWalker, so the same
// tracer measures the GL implementation (over the voxel scene) and what voxelization costs (over
// the exact geometry). With every effect off and no scene lights it is the plain scene model the
// GL ray tracer draws (tests/viewer/scene_render_test.cpp holds the two together).
#pragma once

#include <array>
#include <cstdint>

#include "render/camera.h"
#include "render/image.h"
#include "render/render_settings.h"
#include "render/scene_walker.h"
#include "tf/transfer_function.h"

namespace voxlink::render {

// Rays whose weight falls below 1 - terminationAlpha are not spawned, as a primary ray stops
// once its transmittance does.
class EffectsTracer {
 public:
  // Both must outlive the tracer.
  EffectsTracer(const SceneWalker& scene, const tf::TransferFunction& tf);

  // Rows in parallel; the image holds linear RGB before tone mapping and alpha = 1 - the share
  // of the pixel that reached the background.
  Image render(const Camera& camera, const RenderSettings& settings) const;
  std::array<double, 4> traceRay(const Ray& ray, const Camera& camera,
                                 const RenderSettings& settings) const;

 private:
  struct Frame;
  Frame makeFrame(const Camera& camera, const RenderSettings& settings) const;
  std::array<double, 4> trace(const Ray& primary, const Frame& f) const;
  double shadowTransmittance(const glm::dvec3& point, const glm::dvec3& toLight,
                             double lightDistance, const Frame& f) const;

  const SceneWalker& scene_;
  const tf::TransferFunction& tf_;
};

}  // namespace voxlink::render
