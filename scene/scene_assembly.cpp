#include "scene/scene_assembly.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "format/gradient_codec.h"
#include "format/scene_builder.h"
#include "format/validator.h"
#include "format/voxel_locator.h"
#include "format/voxlink_file.h"
#include "geometry/sphere_voxelizer.h"
#include "geometry/voxel_grid.h"
#include "scene/build_estimate.h"
#include "scene/scene_geometry.h"
#include "scene/scene_volume.h"

namespace voxlink::scene {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// The volume's stored bits of voxel i, as SceneBuilder takes them.
uint32_t storedBits(const format::VoxLinkFile& f, uint64_t i) {
  const size_t size = storedSize(f.valueType());
  uint32_t bits = 0;
  std::memcpy(&bits, f.valueBytes() + i * size, size);  // little-endian host
  return bits;
}

}  // namespace

Result<SceneBuildOutput> buildScene(const SceneDescription& scene, const SceneProgress& progress,
                                    const SurfaceVoxelizer& surfaceVoxelizer) {
  auto stage = [&](const char* name, double fraction) {
    if (progress) progress(name, fraction);
  };
  SceneBuildOutput out;
  SceneBuildReport& report = out.report;
  const auto loadStart = Clock::now();
  stage("load", 0);
  VOXLINK_ASSIGN_OR_RETURN(PlacedScene placed, placeSceneGeometry(scene));
  report.triangles = placed.mesh.triangleCount();
  report.spheres = placed.spheres.size();
  std::optional<format::VoxLinkFile> volume;
  for (const SceneObject* o : placed.volumes) {
    VOXLINK_ASSIGN_OR_RETURN(format::VoxLinkFile f, openSceneVolume(*o, scene.grid));
    if (f.isScene())
      return makeError(
          ErrorCode::kUnsupported, o->path,
          ": a scene (version 2) cannot be a scene's volume; give the volume's own .vxl");
    VOXLINK_RETURN_IF_ERROR(format::validateFile(f).status());
    volume.emplace(std::move(f));
  }
  report.loadSeconds = secondsSince(loadStart);

  // The grid, and the description the file's header is made from.
  format::VolumeDescription d;
  if (volume) {
    const format::FileHeader& h = volume->header();
    for (int a = 0; a < 3; ++a) {
      d.dims[a] = h.dims[a];
      d.spacing[a] = h.spacing[a];
      d.origin[a] = h.origin[a];
    }
    d.brickSize = h.brickSize;
    d.predominantAxis = volume->predominantAxis();
    d.valueType = volume->valueType();
    d.sourceType = volume->sourceType();
    d.valueScale = h.valueScale;
    d.valueOffset = h.valueOffset;
    d.valueMaxAbsError = h.valueMaxAbsError;
    d.valueMaxRelError = h.valueMaxRelError;
    d.valueErrorBound = h.valueErrorBound;
    d.flags = h.flags;
  } else {
    if (placed.mesh.triangleCount() == 0 && placed.spheres.empty())
      return makeError(ErrorCode::kInvalidArgument, scene.path,
                       ": objects: the scene holds no geometry and no volume");
    VOXLINK_ASSIGN_OR_RETURN(geometry::VoxelGrid fitted,
                             geometry::fitGrid(placed.bounds, scene.grid.resolution));
    for (int a = 0; a < 3; ++a) {
      d.dims[a] = fitted.dims[a];
      d.spacing[a] = fitted.spacing;
      d.origin[a] = fitted.origin[a];
    }
    d.brickSize = scene.grid.brickSize;
    d.predominantAxis = scene.grid.axis;
  }
  VOXLINK_RETURN_IF_ERROR(format::checkDescription(d));
  report.dims = d.dims;
  report.spacing = d.spacing;
  const SceneBuildEstimate estimate =
      estimateSceneBuild(placed, d, volume ? volume->voxelCount() : 0);
  VOXLINK_RETURN_IF_ERROR(checkSceneBuildFits(estimate, format::memoryForThisProcess(), scene.path,
                                              scene.grid.resolution, volume.has_value()));

  const auto voxelizeStart = Clock::now();
  stage("voxelize", 0);
  format::SceneBuilder builder(d);
  // Meshes are voxelized in index space (voxel centres on integers, unit voxels), which is exact
  // for anisotropic voxels too: a per-axis scaling keeps which boxes a triangle overlaps. Normals
  // come back to world space through the inverse transpose of that scaling.
  if (placed.mesh.triangleCount() > 0) {
    geometry::TriangleMesh& mesh = placed.mesh;
    mesh.materials.resize(placed.materials.size());
    for (size_t v = 0; v < mesh.vertexCount(); ++v)
      for (int a = 0; a < 3; ++a)
        mesh.positions[3 * v + a] = float((mesh.positions[3 * v + a] - d.origin[a]) / d.spacing[a]);
    geometry::VoxelGrid indexGrid;
    indexGrid.dims = d.dims;
    const auto meshProgress = [&](double f) { stage("voxelize", 0.5 * f); };
    geometry::SurfaceVoxelizeOptions exact;
    exact.progress = meshProgress;
    VOXLINK_ASSIGN_OR_RETURN(geometry::SurfaceVoxelization surface,
                             surfaceVoxelizer ? surfaceVoxelizer(mesh, indexGrid, meshProgress)
                                              : geometry::voxelizeSurface(mesh, indexGrid, exact));
    for (const geometry::SurfaceVoxel& v : surface.voxels) {
      const double n[3] = {v.normal[0] / d.spacing[0], v.normal[1] / d.spacing[1],
                           v.normal[2] / d.spacing[2]};
      builder.addSurface(v.x, v.y, v.z, format::encodeGradient(n[0], n[1], n[2]), v.material);
    }
    report.surfaceVoxels = surface.voxels.size();
    report.normalError = surface.normalError;
    report.zeroAreaTriangles = surface.zeroAreaTriangles;
  }
  stage("voxelize", 0.5);
  std::vector<format::SphereRecord> sphereRecords;
  if (!placed.spheres.empty()) {
    const double s0 = d.spacing[0];
    if (std::abs(d.spacing[1] - s0) > 1e-9 * s0 || std::abs(d.spacing[2] - s0) > 1e-9 * s0)
      return makeError(ErrorCode::kUnsupported, scene.path,
                       ": spheres need cubic voxels; the volume's spacing is ", d.spacing[0], " x ",
                       d.spacing[1], " x ", d.spacing[2]);
    geometry::VoxelGrid grid;
    grid.dims = d.dims;
    grid.origin = d.origin;
    grid.spacing = s0;
    VOXLINK_ASSIGN_OR_RETURN(
        geometry::SphereVoxelization spheres,
        geometry::voxelizeSpheres(placed.spheres, grid, geometry::kDefaultMaxSphereOverlaps,
                                  geometry::SphereFill::kShell));
    for (size_t n = 0; n < spheres.voxels.size(); ++n)
      for (uint64_t r = spheres.offsets[n]; r < spheres.offsets[n + 1]; ++r)
        builder.addSphereRef(spheres.voxels[n][0], spheres.voxels[n][1], spheres.voxels[n][2],
                             spheres.sphereIds[r]);
    report.sphereVoxels = spheres.voxels.size();
    report.sphereRefs = spheres.sphereIds.size();
    for (const geometry::Sphere& s : placed.spheres) {
      format::SphereRecord r{};
      for (int a = 0; a < 3; ++a) r.center[a] = s.center[a];
      r.radius = s.radius;
      r.material = s.material;
      sphereRecords.push_back(r);
    }
  }
  report.voxelizeSeconds = secondsSince(voxelizeStart);

  const auto mergeStart = Clock::now();
  stage("merge", 0);
  nlohmann::ordered_json meta;
  meta["scene"]["file"] = scene.path;
  meta["scene"]["materials"] = placed.materialNames;
  nlohmann::ordered_json objects = nlohmann::ordered_json::array();
  for (const SceneObject& o : scene.objects) {
    static const char* kinds[] = {"mesh", "particles", "sphere", "volume"};
    objects.push_back({{"type", kinds[int(o.kind)]}, {"file", o.path}});
  }
  meta["scene"]["objects"] = objects;
  nlohmann::ordered_json lights = nlohmann::ordered_json::array();
  for (const Light& l : scene.lights)
    lights.push_back({{"position", l.position}, {"color", l.color}, {"intensity", l.intensity}});
  meta["scene"]["lights"] = lights;
  if (!scene.cameraJson.empty())
    meta["scene"]["camera"] = nlohmann::ordered_json::parse(scene.cameraJson);
  meta["scene"]["normal_error_degrees"] = {{"mean", report.normalError.meanDegrees},
                                           {"p95", report.normalError.p95Degrees},
                                           {"max", report.normalError.maxDegrees}};
  if (volume) {
    const format::VoxelLocator locator(*volume);
    const auto gradients = volume->gradientCodes();
    locator.forEachVoxel([&](uint32_t x, uint32_t y, uint32_t z, uint64_t i) {
      builder.addVolumeSample(x, y, z, storedBits(*volume, i), gradients[i]);
    });
    report.volumeVoxels = volume->voxelCount();
    const auto volumeMeta = nlohmann::ordered_json::parse(volume->metaJson(), nullptr, false);
    if (!volumeMeta.is_discarded()) meta["volume"] = volumeMeta;
  }
  builder.setMaterials(placed.materials);
  builder.setSpheres(std::move(sphereRecords));
  report.materials = placed.materials.size();
  VOXLINK_ASSIGN_OR_RETURN(out.volume, builder.build(meta.dump()));
  report.mergeSeconds = secondsSince(mergeStart);
  stage("merge", 1);
  return out;
}

}  // namespace voxlink::scene
