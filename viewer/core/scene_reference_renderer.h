// The float64 reference for scenes (format version 2): the same voxel scene, camera, transfer
// function and shading model as the GL ray tracer's voxel sampling (shaders/voxlink_scene*.glsl),
// evaluated in double precision straight from the file: each cell the ray crosses is looked up
// with format::VoxelLocator, its surface fragment and exact sphere hits are shaded first, its
// volume sample (if any) after, with the exact transfer function. It measures the GL
// implementation; what voxelization itself costs is measured against the original geometry.
#pragma once

#include <array>

#include "format/scene_index.h"
#include "format/transfer_function.h"
#include "format/voxel_locator.h"
#include "format/voxlink_file.h"
#include "viewer/core/camera.h"
#include "viewer/core/image.h"
#include "viewer/core/render_settings.h"

namespace voxlink::viewer {

class SceneReferenceRenderer {
 public:
  // Both must outlive the renderer. Works for version 1 files too (every voxel a volume sample).
  SceneReferenceRenderer(const format::VoxLinkFile& file, const format::TransferFunction& tf);

  // Voxel sampling only, as the GL renderer draws scenes; rows in parallel.
  Image render(const Camera& camera, const RenderSettings& settings) const;
  std::array<double, 4> traceRay(const Ray& ray, const Camera& camera,
                                 const RenderSettings& settings) const;

 private:
  struct Frame;
  struct Hit;
  Frame makeFrame(const Camera& camera, const RenderSettings& settings) const;
  std::array<double, 4> trace(const Ray& ray, const Frame& f) const;
  void compositeSurface(const format::MaterialRecord& m, glm::dvec3 n, const glm::dvec3& indexPoint,
                        const glm::dvec3& toEye, const Frame& f, glm::dvec3& color,
                        double& transmittance) const;
  bool firstSphereHit(uint64_t voxel, const glm::dvec3& o, const glm::dvec3& d, double ta,
                      double tz, Hit& hit) const;
  double geometryTransmittance(uint64_t voxel, const glm::dvec3& o, const glm::dvec3& d, double ta,
                               double tz) const;
  double shadowTransmittance(const glm::dvec3& worldPoint, const Frame& f) const;
  glm::dvec3 toIndex(const glm::dvec3& world) const;
  glm::dvec3 toWorld(const glm::dvec3& index) const;
  glm::dvec3 dirToIndex(const glm::dvec3& dir) const;

  const format::VoxLinkFile& file_;
  const format::TransferFunction& tf_;
  format::VoxelLocator locator_;
  format::SceneIndex index_;
  std::array<uint32_t, 3> dims_;
  glm::dvec3 origin_, spacing_;
};

}  // namespace voxlink::viewer
