// SPDX-License-Identifier: BSD-3-Clause
// The ground truth for image error: a CPU ray caster in float64 over the dense source volume,
// with the same camera, transfer function, sampling and shading model as the GL renderers
// (render_model.h), exact transfer-function evaluation and unquantized gradients.
#pragma once

#include <array>

#include "render/camera.h"
#include "render/dense_volume.h"
#include "render/image.h"
#include "render/render_settings.h"
#include "tf/transfer_function.h"

namespace voxlink::render {

class ReferenceRenderer {
 public:
  // Both must outlive the renderer.
  ReferenceRenderer(const DenseVolume& volume, const tf::TransferFunction& tf);

  // Renders every pixel (in parallel over rows).
  Image render(const Camera& camera, const RenderSettings& settings) const;
  // One pixel's linear RGBA, for tests that probe single rays.
  std::array<double, 4> tracePixel(const Camera& camera, const RenderSettings& settings,
                                   uint32_t px, uint32_t py) const;
  std::array<double, 4> traceRay(const Ray& ray, const Camera& camera,
                                 const RenderSettings& settings) const;

 private:
  struct Frame;
  Frame makeFrame(const Camera& camera, const RenderSettings& settings) const;
  std::array<double, 4> trace(const Ray& ray, const Frame& f) const;
  void traceVoxels(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1, const Frame& f,
                   glm::dvec3& color, double& transmittance) const;
  void traceTrilinear(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
                      const Frame& f, glm::dvec3& color, double& transmittance) const;
  // Transmittance from world point p towards the light (voxel sampling, opacity only).
  double shadowTransmittance(const glm::dvec3& worldPoint, const Frame& f) const;
  // ShadowRays::kPerVoxel: shadowTransmittance from voxel c's centre, through the frame's cache
  // where it has one (render(); single rays compute it).
  double centreShadow(const glm::ivec3& c, const Frame& f) const;
  glm::dvec3 toIndex(const glm::dvec3& world) const;
  glm::dvec3 dirToIndex(const glm::dvec3& dir) const;

  const DenseVolume& volume_;
  const tf::TransferFunction& tf_;
};

}  // namespace voxlink::render
