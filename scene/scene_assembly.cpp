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
#include "geometry/mesh_loader.h"
#include "geometry/particle_loader.h"
#include "geometry/sphere_voxelizer.h"
#include "geometry/voxel_grid.h"
#include "scene/scene_volume.h"

namespace voxlink::scene {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

float clamp01(float v) { return std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f; }

// The file's material record: every value brought into the range the validator accepts.
format::MaterialRecord toRecord(const geometry::Material& m, float specular, float shininess) {
  format::MaterialRecord r{};
  for (int c = 0; c < 3; ++c) {
    r.color[c] = clamp01(m.color[c]);
    r.emission[c] = std::isfinite(m.emission[c]) ? std::max(0.0f, m.emission[c]) : 0.0f;
  }
  r.opacity = clamp01(m.opacity);
  r.reflectivity = clamp01(m.reflectivity);
  r.transmission = clamp01(m.transmission);
  const float sum = r.reflectivity + r.transmission;
  if (sum > 1.0f) {
    r.reflectivity /= sum;
    r.transmission = 1.0f - r.reflectivity;
  }
  r.refractiveIndex =
      std::isfinite(m.refractiveIndex) ? std::clamp(m.refractiveIndex, 1.0f, 10.0f) : 1.0f;
  r.specular = clamp01(specular);
  r.shininess = std::isfinite(shininess) ? std::clamp(shininess, 0.0f, 1e6f) : 0.0f;
  return r;
}

// CPK colours of the common elements of biomolecules (Corey-Pauling-Koltun, as molecular
// viewers use them); anything else is pink.
std::array<float, 3> cpkColor(const std::string& element) {
  if (element == "C") return {0.56f, 0.56f, 0.56f};
  if (element == "O") return {0.94f, 0.16f, 0.16f};
  if (element == "N") return {0.19f, 0.31f, 0.97f};
  if (element == "S") return {1.0f, 0.78f, 0.2f};
  if (element == "H") return {0.95f, 0.95f, 0.95f};
  if (element == "P") return {1.0f, 0.5f, 0.0f};
  return {1.0f, 0.55f, 0.75f};
}

// The scene's one material table: scene materials by name first, then what files bring.
class MaterialTable {
 public:
  explicit MaterialTable(const SceneDescription& scene) : scene_(scene) {
    for (const auto& [name, m] : scene.materials)
      add(name, toRecord(m.material, m.specular, m.shininess));
  }
  uint16_t named(const std::string& name) const {
    for (size_t i = 0; i < names_.size(); ++i)
      if (names_[i] == name) return static_cast<uint16_t>(i);
    return 0;
  }
  bool has(const std::string& name) const { return scene_.findMaterial(name) != nullptr; }
  uint16_t add(const std::string& name, const format::MaterialRecord& record) {
    names_.push_back(name);
    records_.push_back(record);
    return static_cast<uint16_t>(records_.size() - 1);
  }
  size_t size() const { return records_.size(); }
  std::vector<format::MaterialRecord> records() const { return records_; }
  const std::vector<std::string>& names() const { return names_; }

 private:
  const SceneDescription& scene_;
  std::vector<std::string> names_;
  std::vector<format::MaterialRecord> records_;
};

struct PlacedGeometry {
  geometry::TriangleMesh mesh;            // world coordinates, materials of the scene table
  std::vector<geometry::Sphere> spheres;  // world coordinates, materials of the scene table
  geometry::Bounds3 bounds;
};

void grow(geometry::Bounds3& b, double x, double y, double z, double r = 0) {
  const double p[3] = {x, y, z};
  for (int a = 0; a < 3; ++a) {
    b.min[a] = std::min(b.min[a], float(p[a] - r));
    b.max[a] = std::max(b.max[a], float(p[a] + r));
  }
}

Status placeMesh(const SceneObject& o, MaterialTable& table, PlacedGeometry& out,
                 SceneBuildReport& report) {
  VOXLINK_ASSIGN_OR_RETURN(geometry::TriangleMesh mesh, geometry::loadMesh(o.path));
  std::vector<uint16_t> materialOf(mesh.materials.size());
  for (size_t m = 0; m < mesh.materials.size(); ++m)
    materialOf[m] = o.material
                        ? table.named(*o.material)
                        : table.add(mesh.materials[m].name, toRecord(mesh.materials[m], 0, 0));
  if (table.size() > format::kMaxMaterials)
    return makeError(ErrorCode::kTooLarge, o.path, ": the scene has more than ",
                     format::kMaxMaterials, " materials");
  const uint32_t base = static_cast<uint32_t>(out.mesh.vertexCount());
  for (size_t v = 0; v < mesh.vertexCount(); ++v) {
    const auto p = o.transform.apply(
        {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]});
    for (double c : p) out.mesh.positions.push_back(static_cast<float>(c));
  }
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = mesh.triangles[3 * t + c];
      out.mesh.triangles.push_back(base + v);
      const float* p = &out.mesh.positions[3 * (base + v)];
      grow(out.bounds, p[0], p[1], p[2]);
    }
    const uint16_t m = mesh.triangleMaterials.empty() ? 0 : mesh.triangleMaterials[t];
    out.mesh.triangleMaterials.push_back(materialOf.empty() ? table.named(o.material.value_or(""))
                                                            : materialOf[m]);
  }
  report.triangles += mesh.triangleCount();
  return Status::ok();
}

Status placeSpheres(const SceneObject& o, MaterialTable& table, PlacedGeometry& out,
                    SceneBuildReport& report) {
  const double scale = o.transform.uniformScale();
  std::vector<geometry::Sphere> spheres;
  std::vector<uint16_t> materialOf;
  if (o.kind == ObjectKind::kSphere) {
    geometry::Sphere s;
    for (int a = 0; a < 3; ++a) s.center[a] = float(o.center[a]);
    s.radius = float(o.radius);
    spheres.push_back(s);
    materialOf.push_back(o.material ? table.named(*o.material)
                                    : table.add("sphere", toRecord({}, 0, 0)));
  } else {
    VOXLINK_ASSIGN_OR_RETURN(geometry::ParticleSet set, geometry::loadParticles(o.path));
    spheres = std::move(set.spheres);
    for (const std::string& name : set.materials) {
      if (o.material) {
        materialOf.push_back(table.named(*o.material));
      } else if (table.has(name)) {
        materialOf.push_back(table.named(name));
      } else {
        geometry::Material m;
        m.name = name;
        m.color = cpkColor(name);
        materialOf.push_back(table.add(name, toRecord(m, 0.3f, 32.0f)));
      }
    }
    if (materialOf.empty()) materialOf.push_back(table.add("particle", toRecord({}, 0, 0)));
  }
  if (table.size() > format::kMaxMaterials)
    return makeError(ErrorCode::kTooLarge, o.path, ": the scene has more than ",
                     format::kMaxMaterials, " materials");
  for (geometry::Sphere s : spheres) {
    const auto c = o.transform.apply({s.center[0], s.center[1], s.center[2]});
    for (int a = 0; a < 3; ++a) s.center[a] = float(c[a]);
    s.radius = float(s.radius * scale * o.radiusScale);
    s.material = materialOf[std::min<size_t>(s.material, materialOf.size() - 1)];
    grow(out.bounds, c[0], c[1], c[2], s.radius);
    out.spheres.push_back(s);
  }
  report.spheres += spheres.size();
  return Status::ok();
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
  MaterialTable table(scene);
  PlacedGeometry placed;
  std::optional<format::VoxLinkFile> volume;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    stage("load", double(i) / scene.objects.size());
    switch (o.kind) {
      case ObjectKind::kMesh:
        VOXLINK_RETURN_IF_ERROR(placeMesh(o, table, placed, report));
        break;
      case ObjectKind::kParticles:
      case ObjectKind::kSphere:
        VOXLINK_RETURN_IF_ERROR(placeSpheres(o, table, placed, report));
        break;
      case ObjectKind::kVolume: {
        VOXLINK_ASSIGN_OR_RETURN(format::VoxLinkFile f, openSceneVolume(o, scene.grid));
        if (f.isScene())
          return makeError(
              ErrorCode::kUnsupported, o.path,
              ": a scene (version 2) cannot be a scene's volume; give the volume's own .vxl");
        VOXLINK_RETURN_IF_ERROR(format::validateFile(f).status());
        volume.emplace(std::move(f));
        break;
      }
    }
  }
  if (table.size() == 0) table.add("default", toRecord({}, 0, 0));
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

  const auto voxelizeStart = Clock::now();
  stage("voxelize", 0);
  format::SceneBuilder builder(d);
  // Meshes are voxelized in index space (voxel centres on integers, unit voxels), which is exact
  // for anisotropic voxels too: a per-axis scaling keeps which boxes a triangle overlaps. Normals
  // come back to world space through the inverse transpose of that scaling.
  if (placed.mesh.triangleCount() > 0) {
    geometry::TriangleMesh& mesh = placed.mesh;
    mesh.materials.resize(table.size());
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
  meta["scene"]["materials"] = table.names();
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
  builder.setMaterials(table.records());
  builder.setSpheres(std::move(sphereRecords));
  report.materials = table.size();
  VOXLINK_ASSIGN_OR_RETURN(out.volume, builder.build(meta.dump()));
  report.mergeSeconds = secondsSince(mergeStart);
  stage("merge", 1);
  return out;
}

}  // namespace voxlink::scene
