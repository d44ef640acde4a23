// The ground truth for image error: a CPU ray caster in float64 over the dense source volume,
// with the same camera, transfer function, sampling and shading model as the GL renderers
// (render_model.h), exact transfer-function evaluation and unquantized gradients.
#pragma once

#include <array>

#include "format/transfer_function.h"
#include "viewer/core/camera.h"
#include "viewer/core/dense_volume.h"
#include "viewer/core/image.h"
#include "viewer/core/render_settings.h"

namespace voxlink::viewer {

class ReferenceRenderer {
 public:
  // Both must outlive the renderer.
  ReferenceRenderer(const DenseVolume& volume, const format::TransferFunction& tf);

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
  glm::dvec3 toIndex(const glm::dvec3& world) const;
  glm::dvec3 dirToIndex(const glm::dvec3& dir) const;

  const DenseVolume& volume_;
  const format::TransferFunction& tf_;
};

}  // namespace voxlink::viewer
