// SPDX-License-Identifier: BSD-3-Clause
#include "scene/scene_assembly.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "format/gradient_codec.h"
#include "format/scene_builder.h"
#include "format/surface_mode.h"
#include "format/validator.h"
#include "format/voxel_locator.h"
#include "format/voxlink_file.h"
#include "geometry/sphere_voxelizer.h"
#include "geometry/voxel_grid.h"
#include "scene/detail/build_estimate.h"
#include "scene/detail/scene_ranks.h"
#include "scene/detail/scene_volume.h"
#include "scene/detail/surface_fragments.h"
#include "scene/scene_geometry.h"

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

// The grid and the description the file's header is made from: the volume's, or one fitted
// around the geometry.
Result<format::VolumeDescription> describeGrid(const SceneDescription& scene,
                                               const PlacedScene& placed,
                                               const format::VoxLinkFile* volume) {
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
    if (placed.mesh.triangleCount() == 0 && placed.spheres.empty() && !scene.grid.fitBounds)
      return makeError(ErrorCode::kInvalidArgument, scene.path,
                       ": objects: the scene holds no geometry and no volume");
    VOXLINK_ASSIGN_OR_RETURN(
        geometry::VoxelGrid fitted,
        geometry::fitGrid(scene.grid.fitBounds.value_or(placed.bounds), scene.grid.resolution));
    for (int a = 0; a < 3; ++a) {
      d.dims[a] = fitted.dims[a];
      d.spacing[a] = fitted.spacing;
      d.origin[a] = fitted.origin[a];
    }
    d.brickSize = scene.grid.brickSize;
    d.predominantAxis = scene.grid.axis;
  }
  VOXLINK_RETURN_IF_ERROR(format::checkDescription(d));
  const SceneBuildEstimate estimate =
      estimateSceneBuild(placed, d, volume ? volume->voxelCount() : 0);
  VOXLINK_RETURN_IF_ERROR(checkSceneBuildFits(estimate, base::memoryForThisProcess(), scene.path,
                                              scene.grid.resolution, volume != nullptr));
  return d;
}

// Rank 0's volume object, opened and validated (the last one the scene names).
Status openVolume(const PlacedScene& placed, const SceneGrid& grid,
                  std::optional<format::VoxLinkFile>& volume) {
  for (const SceneObject* o : placed.volumes) {
    VOXLINK_ASSIGN_OR_RETURN(format::VoxLinkFile f, openSceneVolume(*o, grid));
    if (f.isScene())
      return makeError(
          ErrorCode::kUnsupported, o->path,
          ": a scene (version 2) cannot be a scene's volume; give the volume's own .vxl");
    VOXLINK_RETURN_IF_ERROR(format::validateFile(f).status());
    volume.emplace(std::move(f));
  }
  return Status::ok();
}

// The meshes and spheres of `placed` in the slices `slab` of the grid `d`.
Status voxelizeSlab(const SceneDescription& scene, PlacedScene& placed,
                    const format::VolumeDescription& d, geometry::ZSlab slab,
                    const SurfaceVoxelizer& surfaceVoxelizer,
                    const std::function<void(double)>& meshProgress, SceneBuildReport& report,
                    SlabVoxels& out) {
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
    const format::SurfaceMode mode = scene.grid.surface;
    if (surfaceVoxelizer && mode != format::SurfaceMode::kMean)
      return makeError(ErrorCode::kUnsupported,
                       "scene build: the GL voxelizer keeps one fragment per voxel; use "
                       "--voxelizer exact with --surface planes or triangles");
    geometry::SurfaceVoxelizeOptions exact;
    exact.progress = meshProgress;
    exact.slab = slab;
    exact.keepTriangleLists = mode != format::SurfaceMode::kMean;
    exact.computeNormalError = mode == format::SurfaceMode::kMean;
    VOXLINK_ASSIGN_OR_RETURN(geometry::SurfaceVoxelization surface,
                             surfaceVoxelizer ? surfaceVoxelizer(mesh, indexGrid, meshProgress)
                                              : geometry::voxelizeSurface(mesh, indexGrid, exact));
    out.surface.reserve(surface.voxels.size());
    for (const geometry::SurfaceVoxel& v : surface.voxels) {
      const double n[3] = {v.normal[0] / d.spacing[0], v.normal[1] / d.spacing[1],
                           v.normal[2] / d.spacing[2]};
      out.surface.push_back({v.x, v.y, v.z, format::encodeGradient(n[0], n[1], n[2]), v.material});
    }
    if (surface.normalTally) out.normalError = *surface.normalTally;
    report.zeroAreaTriangles = surface.zeroAreaTriangles;
    if (mode != format::SurfaceMode::kMean)
      VOXLINK_RETURN_IF_ERROR(
          appendFragmentLists(mode, scene.grid.fragmentAngleDegrees, mesh, d, surface, out));
  }
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
                                  geometry::SphereFill::kShell, slab));
    out.sphereRefs.reserve(spheres.sphereIds.size());
    for (size_t n = 0; n < spheres.voxels.size(); ++n)
      for (uint64_t r = spheres.offsets[n]; r < spheres.offsets[n + 1]; ++r)
        out.sphereRefs.push_back({spheres.voxels[n][0], spheres.voxels[n][1], spheres.voxels[n][2],
                                  spheres.sphereIds[r]});
    out.sphereVoxels = spheres.voxels.size();
  }
  return Status::ok();
}

}  // namespace

Result<SceneBuildOutput> buildScene(const SceneDescription& scene, const SceneProgress& progress,
                                    const SurfaceVoxelizer& surfaceVoxelizer,
                                    base::RankGroup* group) {
  base::RankGroup& ranks = group ? *group : base::singleProcess();
  const bool root = ranks.rank() == 0;
  auto stage = [&](const char* name, double fraction) {
    if (progress) progress(name, fraction);
  };
  SceneBuildOutput out;
  SceneBuildReport& report = out.report;
  const auto loadStart = Clock::now();
  stage("load", 0);
  // Every rank loads and places the geometry itself (inputs are small next to the voxels);
  // every step that needs the others is preceded by an agreement, so a failing rank ends all.
  auto placedOr = placeSceneGeometry(scene);
  Status loaded = placedOr.status();
  if (loaded && surfaceVoxelizer && ranks.size() > 1)
    loaded = makeError(ErrorCode::kUnsupported,
                       "scene build: the GL voxelizer runs in one process; use --voxelizer exact "
                       "on several MPI ranks");
  VOXLINK_RETURN_IF_ERROR(base::agree(ranks, loaded));
  PlacedScene& placed = *placedOr;
  VOXLINK_RETURN_IF_ERROR(checkSameGeometry(ranks, placed, scene.path));
  // The triangles in world units, before voxelizeSlab moves the mesh into index space.
  std::vector<format::TriangleRecord> triangleTable;
  if (root && scene.grid.surface == format::SurfaceMode::kTriangles)
    triangleTable = triangleRecords(placed.mesh);
  report.triangles = placed.mesh.triangleCount();
  report.spheres = placed.spheres.size();
  // Rank 0 alone opens the volume (a dense one is converted there) and fixes the grid.
  std::optional<format::VoxLinkFile> volume;
  format::VolumeDescription d;
  Status described = Status::ok();
  if (root) {
    described = openVolume(placed, scene.grid, volume);
    if (described) {
      auto grid = describeGrid(scene, placed, volume ? &*volume : nullptr);
      if (grid) d = *grid;
      described = grid.status();
    }
  }
  VOXLINK_RETURN_IF_ERROR(base::agree(ranks, described));
  broadcastDescription(ranks, d);
  report.loadSeconds = secondsSince(loadStart);
  report.dims = d.dims;
  report.spacing = d.spacing;

  const auto voxelizeStart = Clock::now();
  stage("voxelize", 0);
  SlabVoxels slab;
  const Status voxelized = voxelizeSlab(
      scene, placed, d, rankSlab(d.dims[2], d.brickSize, ranks.rank(), ranks.size()),
      surfaceVoxelizer, [&](double f) { stage("voxelize", f); }, report, slab);
  VOXLINK_RETURN_IF_ERROR(base::agree(ranks, voxelized));
  report.voxelizeSeconds = secondsSince(voxelizeStart);

  const auto mergeStart = Clock::now();
  stage("merge", 0);
  slab = gatherSlabVoxels(ranks, std::move(slab));
  if (!root) return out;  // rank 0 alone holds the merged voxels and the file
  report.surfaceVoxels = slab.surface.size();
  report.normalError = slab.normalError.stats();
  report.surfaceMode = scene.grid.surface;
  report.fragments = slab.planes.size() + slab.triangleRefs.size();
  report.maxPlaneOffsetError = slab.maxOffsetError;
  report.planePairsLeftOut = slab.planePairsLeftOut;
  report.sphereVoxels = slab.sphereVoxels;
  report.sphereRefs = slab.sphereRefs.size();
  format::SceneBuilder builder(d);
  builder.reserve(slab.surface.size() + slab.sphereRefs.size() +
                  (volume ? volume->voxelCount() : 0));
  for (const SurfaceEntry& e : slab.surface)
    builder.addSurface(e.x, e.y, e.z, e.normalCode, e.material);
  if (scene.grid.surface != format::SurfaceMode::kMean) {
    builder.setSurfaceMode(scene.grid.surface);
    builder.setTriangles(std::move(triangleTable));
    size_t at = 0;
    for (size_t i = 0; i < slab.surface.size(); ++i) {
      const SurfaceEntry& e = slab.surface[i];
      const uint32_t n = slab.listLength[i];
      if (scene.grid.surface == format::SurfaceMode::kPlanes)
        builder.addFragments(e.x, e.y, e.z, std::span(slab.planes).subspan(at, n));
      else
        builder.addTriangleRefs(e.x, e.y, e.z, std::span(slab.triangleRefs).subspan(at, n));
      at += n;
    }
  }
  std::vector<SurfaceEntry>().swap(slab.surface);
  for (const SphereEntry& e : slab.sphereRefs) builder.addSphereRef(e.x, e.y, e.z, e.sphere);
  std::vector<SphereEntry>().swap(slab.sphereRefs);
  std::vector<format::SphereRecord> sphereRecords;
  for (const geometry::Sphere& s : placed.spheres) {
    format::SphereRecord r{};
    for (int a = 0; a < 3; ++a) r.center[a] = s.center[a];
    r.radius = s.radius;
    r.material = s.material;
    sphereRecords.push_back(r);
  }
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
  // Only files with fragment lists say so, so that `--surface mean` writes the bytes it did.
  if (scene.grid.surface != format::SurfaceMode::kMean) {
    meta["scene"]["surface"] = {{"mode", format::surfaceModeName(scene.grid.surface)},
                                {"fragments", report.fragments}};
    if (scene.grid.surface == format::SurfaceMode::kPlanes) {
      meta["scene"]["surface"]["fragment_angle_degrees"] = scene.grid.fragmentAngleDegrees;
      meta["scene"]["surface"]["plane_offset_max_error_voxels"] = report.maxPlaneOffsetError;
      meta["scene"]["surface"]["pairs_without_plane"] = report.planePairsLeftOut;
    }
  }
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
