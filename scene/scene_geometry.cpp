// SPDX-License-Identifier: BSD-3-Clause
#include "scene/scene_geometry.h"

#include <algorithm>
#include <cmath>

#include "geometry/mesh_loader.h"
#include "geometry/particle_loader.h"

namespace voxlink::scene {
namespace {

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

void grow(geometry::Bounds3& b, double x, double y, double z, double r = 0) {
  const double p[3] = {x, y, z};
  for (int a = 0; a < 3; ++a) {
    b.min[a] = std::min(b.min[a], float(p[a] - r));
    b.max[a] = std::max(b.max[a], float(p[a] + r));
  }
}

Status placeMesh(const SceneObject& o, MaterialTable& table, PlacedScene& out) {
  VOXLINK_ASSIGN_OR_RETURN(geometry::TriangleMesh mesh, geometry::loadMesh(o.path));
  std::vector<uint16_t> materialOf(mesh.materials.size());
  for (size_t m = 0; m < mesh.materials.size(); ++m)
    materialOf[m] = o.material
                        ? table.named(*o.material)
                        : table.add(mesh.materials[m].name, toRecord(mesh.materials[m], 0, 0));
  if (table.size() > format::kMaxMaterials)
    return makeError(ErrorCode::kTooLarge, "the scene has more than ", format::kMaxMaterials,
                     " materials");
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
  return Status::ok();
}

Status placeSpheres(const SceneObject& o, MaterialTable& table, PlacedScene& out) {
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
    return makeError(ErrorCode::kTooLarge, "the scene has more than ", format::kMaxMaterials,
                     " materials");
  for (geometry::Sphere s : spheres) {
    const auto c = o.transform.apply({s.center[0], s.center[1], s.center[2]});
    for (int a = 0; a < 3; ++a) s.center[a] = float(c[a]);
    s.radius = float(s.radius * scale * o.radiusScale);
    s.material = materialOf[std::min<size_t>(s.material, materialOf.size() - 1)];
    grow(out.bounds, c[0], c[1], c[2], s.radius);
    out.spheres.push_back(s);
  }
  return Status::ok();
}

}  // namespace

Result<PlacedScene> placeSceneGeometry(const SceneDescription& scene) {
  PlacedScene placed;
  MaterialTable table(scene);
  for (const SceneObject& o : scene.objects) {
    Status placedObject;
    switch (o.kind) {
      case ObjectKind::kMesh:
        placedObject = placeMesh(o, table, placed);
        break;
      case ObjectKind::kParticles:
      case ObjectKind::kSphere:
        placedObject = placeSpheres(o, table, placed);
        break;
      case ObjectKind::kVolume:
        placed.volumes.push_back(&o);
        break;
    }
    // Named by the scene file and the object ("cornell.scene.json: objects[2]: bunny.obj: ..."),
    // as docs/scene.md promises: a scene names many files.
    if (!placedObject)
      return o.where.empty() ? placedObject.error()
                             : makeError(placedObject.error().code, o.where, ": ",
                                         placedObject.error().message);
  }
  if (table.size() == 0) table.add("default", toRecord({}, 0, 0));
  placed.materialNames = table.names();
  placed.materials = table.records();
  return placed;
}

}  // namespace voxlink::scene
