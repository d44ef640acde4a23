// SPDX-License-Identifier: BSD-3-Clause
#include "scene/scene_description.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace voxlink::scene {
namespace {

using nlohmann::json;
constexpr double kPi = 3.14159265358979323846;

// Reads fields of one JSON object; the first problem is kept and named by its JSON path.
class Fields {
 public:
  Fields(const std::string& file, Status& status) : file_(file), status_(status) {}

  bool ok() const { return status_.isOk(); }
  const std::string& file() const { return file_; }
  void fail(const std::string& where, const std::string& what) {
    if (ok()) status_ = makeError(ErrorCode::kInvalidArgument, file_, ": ", where, ": ", what);
  }

  double number(const json& j, const std::string& where, double lo, double hi) {
    if (!j.is_number()) {
      fail(where, "expected a number");
      return lo;
    }
    const double v = j.get<double>();
    if (!std::isfinite(v) || v < lo || v > hi) {
      std::ostringstream range;
      range << v << " is not in [" << lo << ", " << hi << "]";
      fail(where, range.str());
      return lo;  // in range, so a caller's integer or float cast stays defined
    }
    return v;
  }
  template <size_t N>
  std::array<double, N> vector(const json& j, const std::string& where, double lo, double hi) {
    std::array<double, N> out{};
    if (!j.is_array() || j.size() != N) {
      fail(where, "expected an array of " + std::to_string(N) + " numbers");
      return out;
    }
    for (size_t i = 0; i < N; ++i)
      out[i] = number(j[i], where + "[" + std::to_string(i) + "]", lo, hi);
    return out;
  }
  std::string string(const json& j, const std::string& where) {
    if (!j.is_string()) {
      fail(where, "expected a string");
      return {};
    }
    return j.get<std::string>();
  }
  // Fails on keys the reader does not know: a typo must not be silently ignored.
  void onlyKeys(const json& j, const std::string& where, std::initializer_list<const char*> keys) {
    if (!j.is_object()) {
      fail(where, "expected an object");
      return;
    }
    for (const auto& [key, value] : j.items()) {
      bool known = false;
      for (const char* k : keys) known = known || key == k;
      if (!known) fail(where + "." + key, "unknown field");
    }
  }

 private:
  const std::string& file_;
  Status& status_;
};

Transform multiply(const Transform& a, const Transform& b) {
  Transform r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a.m[i * 4 + k] * b.m[k * 4 + j];
      r.m[i * 4 + j] = s;
    }
  return r;
}

Transform rotation(int axis, double degrees) {
  const double c = std::cos(degrees * kPi / 180), s = std::sin(degrees * kPi / 180);
  Transform r;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  r.m[u * 4 + u] = c;
  r.m[u * 4 + v] = -s;
  r.m[v * 4 + u] = s;
  r.m[v * 4 + v] = c;
  return r;
}

// "transform": {"scale": s | [sx, sy, sz], "rotate": [degrees about x, y, z], "translate": [..]}
// applied in that order (scale, then rotations about x, y, z, then translation), or
// {"matrix": [16 numbers, row-major]}.
Transform readTransform(const json& j, const std::string& where, Fields& f) {
  Transform t;
  f.onlyKeys(j, where, {"scale", "rotate", "translate", "matrix"});
  if (!f.ok()) return t;
  if (j.contains("matrix")) {
    if (j.size() != 1) f.fail(where, "\"matrix\" excludes scale, rotate and translate");
    const auto m = f.vector<16>(j["matrix"], where + ".matrix", -1e12, 1e12);
    if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1)
      f.fail(where + ".matrix", "last row must be 0 0 0 1 (an affine transform)");
    t.m = m;
    return t;
  }
  if (j.contains("scale")) {
    std::array<double, 3> s{};
    if (j["scale"].is_number()) {
      s.fill(f.number(j["scale"], where + ".scale", 1e-12, 1e12));
    } else {
      s = f.vector<3>(j["scale"], where + ".scale", 1e-12, 1e12);
    }
    Transform scale;
    for (int a = 0; a < 3; ++a) scale.m[a * 5] = s[a];
    t = multiply(scale, t);
  }
  if (j.contains("rotate")) {
    const auto r = f.vector<3>(j["rotate"], where + ".rotate", -3600, 3600);
    for (int a = 0; a < 3; ++a) t = multiply(rotation(a, r[a]), t);
  }
  if (j.contains("translate")) {
    const auto d = f.vector<3>(j["translate"], where + ".translate", -1e12, 1e12);
    for (int a = 0; a < 3; ++a) t.m[a * 4 + 3] += d[a];
  }
  return t;
}

SceneMaterial readMaterial(const json& j, const std::string& where, Fields& f) {
  SceneMaterial out;
  f.onlyKeys(j, where,
             {"color", "opacity", "emission", "reflectivity", "transmission", "ior", "specular",
              "shininess"});
  if (!f.ok()) return out;
  geometry::Material& m = out.material;
  if (j.contains("color")) {
    const auto c = f.vector<3>(j["color"], where + ".color", 0, 1);
    m.color = {float(c[0]), float(c[1]), float(c[2])};
  }
  if (j.contains("emission")) {
    const auto e = f.vector<3>(j["emission"], where + ".emission", 0, 1e6);
    m.emission = {float(e[0]), float(e[1]), float(e[2])};
  }
  if (j.contains("opacity")) m.opacity = float(f.number(j["opacity"], where + ".opacity", 0, 1));
  if (j.contains("reflectivity"))
    m.reflectivity = float(f.number(j["reflectivity"], where + ".reflectivity", 0, 1));
  if (j.contains("transmission"))
    m.transmission = float(f.number(j["transmission"], where + ".transmission", 0, 1));
  if (j.contains("ior")) m.refractiveIndex = float(f.number(j["ior"], where + ".ior", 1, 10));
  if (j.contains("specular"))
    out.specular = float(f.number(j["specular"], where + ".specular", 0, 1));
  if (j.contains("shininess"))
    out.shininess = float(f.number(j["shininess"], where + ".shininess", 0, 1e6));
  if (m.reflectivity + m.transmission > 1.0f) f.fail(where, "reflectivity + transmission exceed 1");
  return out;
}

// "animation": {"keys": [{"time": s, "translate": [..], "rotate": [..]}, ...], "period": s}.
Animation readAnimation(const json& j, const std::string& where, Fields& f) {
  Animation a;
  f.onlyKeys(j, where, {"keys", "period"});
  if (!f.ok()) return a;
  if (!j.contains("keys") || !j["keys"].is_array() || j["keys"].empty()) {
    f.fail(where + ".keys", "expected an array of at least one key");
    return a;
  }
  for (size_t i = 0; f.ok() && i < j["keys"].size(); ++i) {
    const json& k = j["keys"][i];
    const std::string at = cat(where, ".keys[", i, "]");
    f.onlyKeys(k, at, {"time", "translate", "rotate"});
    if (f.ok() && !k.contains("time")) f.fail(at, "needs a \"time\"");
    if (!f.ok()) break;
    AnimationKey key;
    key.time = f.number(k["time"], at + ".time", 0, 1e9);
    if (k.contains("translate"))
      key.translate = f.vector<3>(k["translate"], at + ".translate", -1e12, 1e12);
    if (k.contains("rotate"))
      key.rotateDegrees = f.vector<3>(k["rotate"], at + ".rotate", -3600, 3600);
    if (f.ok() && i > 0 && key.time <= a.keys.back().time)
      f.fail(at + ".time", cat(key.time, " is not after keys[", i - 1, "].time (",
                               a.keys.back().time, "): keys must be sorted by time"));
    a.keys.push_back(key);
  }
  if (f.ok() && j.contains("period")) {
    a.period = f.number(j["period"], where + ".period", 1e-9, 1e9);
    if (f.ok() && a.period <= a.keys.back().time)
      f.fail(where + ".period",
             cat(a.period, " is not after the last key's time (", a.keys.back().time, ")"));
  }
  return a;
}

// "threshold": 60, [60, 200], or a list of those (a union): convert's --threshold specs.
std::vector<std::string> thresholdSpecs(Fields& f, const json& j, const std::string& where) {
  const std::string at = where + ".threshold";
  auto spec = [&](const json& one, const std::string& path) -> std::string {
    char text[64];
    if (one.is_number()) {
      std::snprintf(text, sizeof text, "%.17g", f.number(one, path, -1e300, 1e300));
      return text;
    }
    if (!one.is_array() || one.empty() || one.size() > 2 || !one[0].is_number()) {
      f.fail(path, "a threshold is LO or [LO, HI]");
      return {};
    }
    const double lo = f.number(one[0], path + "[0]", -1e300, 1e300);
    if (one.size() == 1) {
      std::snprintf(text, sizeof text, "%.17g", lo);
    } else {
      const double hi = f.number(one[1], path + "[1]", -1e300, 1e300);
      if (f.ok() && hi < lo) f.fail(path, "HI is below LO");
      std::snprintf(text, sizeof text, "%.17g,%.17g", lo, hi);
    }
    return text;
  };
  std::vector<std::string> out;
  if (j.is_array() && !j.empty() && j[0].is_array()) {
    for (size_t i = 0; i < j.size(); ++i) out.push_back(spec(j[i], cat(at, "[", i, "]")));
  } else {
    out.push_back(spec(j, at));
  }
  return out;
}

SceneObject readObject(const json& j, const std::string& where, const std::filesystem::path& base,
                       const SceneDescription& scene, Fields& f) {
  SceneObject o;
  o.where = f.file() + ": " + where;
  if (!j.is_object() || !j.contains("type")) {
    f.fail(where, "expected an object with a \"type\" (mesh, particles, sphere or volume)");
    return o;
  }
  const std::string type = f.string(j["type"], where + ".type");
  if (f.ok() && j.contains("animation") && type == "volume")
    f.fail(where + ".animation",
           "only meshes, sphere sets and particles move (a volume is not re-voxelized)");
  if (type == "mesh" || type == "particles") {
    o.kind = type == "mesh" ? ObjectKind::kMesh : ObjectKind::kParticles;
    if (type == "mesh")
      f.onlyKeys(j, where, {"type", "file", "transform", "material", "animation"});
    else
      f.onlyKeys(j, where, {"type", "file", "transform", "material", "radius_scale", "animation"});
    if (j.contains("radius_scale"))
      o.radiusScale = f.number(j["radius_scale"], where + ".radius_scale", 1e-6, 1e6);
  } else if (type == "sphere") {
    o.kind = ObjectKind::kSphere;
    f.onlyKeys(j, where, {"type", "center", "radius", "transform", "material", "animation"});
    if (!j.contains("center") || !j.contains("radius"))
      f.fail(where, "a sphere needs \"center\" and \"radius\"");
    if (!f.ok()) return o;
    o.center = f.vector<3>(j["center"], where + ".center", -1e12, 1e12);
    o.radius = f.number(j["radius"], where + ".radius", 1e-12, 1e12);
  } else if (type == "volume") {
    o.kind = ObjectKind::kVolume;
    f.onlyKeys(j, where, {"type", "file", "threshold", "tf"});
    if (j.contains("threshold") && j.contains("tf"))
      f.fail(where, "give \"threshold\" or \"tf\", not both");
    if (j.contains("threshold")) o.thresholds = thresholdSpecs(f, j["threshold"], where);
    if (j.contains("tf")) {
      const std::filesystem::path tf = f.string(j["tf"], where + ".tf");
      o.tfPath = (tf.is_absolute() ? tf : base / tf).lexically_normal().string();
    }
  } else {
    f.fail(where + ".type", "\"" + type + "\" is not mesh, particles, sphere or volume");
  }
  if (!f.ok()) return o;
  if (o.kind != ObjectKind::kSphere) {
    if (!j.contains("file")) {
      f.fail(where, "needs a \"file\"");
      return o;
    }
    const std::filesystem::path file = f.string(j["file"], where + ".file");
    o.path = (file.is_absolute() ? file : base / file).lexically_normal().string();
  }
  if (j.contains("transform")) o.transform = readTransform(j["transform"], where + ".transform", f);
  if (j.contains("material")) {
    o.material = f.string(j["material"], where + ".material");
    if (f.ok() && !scene.findMaterial(*o.material))
      f.fail(where + ".material", "\"" + *o.material + "\" is not in \"materials\"");
  }
  if (f.ok() && j.contains("animation")) {
    if (!o.material)
      f.fail(where + ".animation", o.kind == ObjectKind::kMesh
                                       ? "a moving mesh needs a \"material\" from \"materials\""
                                       : "moving spheres need a \"material\" from \"materials\"");
    else
      o.animation = readAnimation(j["animation"], where + ".animation", f);
  }
  if (f.ok() && o.kind == ObjectKind::kParticles && o.transform.uniformScale() == 0)
    f.fail(where + ".transform", "spheres need a uniform scale");
  if (f.ok() && o.kind == ObjectKind::kSphere && o.transform.uniformScale() == 0)
    f.fail(where + ".transform", "spheres need a uniform scale");
  return o;
}

}  // namespace

std::array<double, 3> Transform::apply(const std::array<double, 3>& p) const {
  std::array<double, 3> r{};
  for (int i = 0; i < 3; ++i)
    r[i] = m[i * 4] * p[0] + m[i * 4 + 1] * p[1] + m[i * 4 + 2] * p[2] + m[i * 4 + 3];
  return r;
}

double Transform::uniformScale() const {
  // Columns of the linear part must be orthogonal and of equal length.
  double len[3];
  for (int c = 0; c < 3; ++c)
    len[c] = std::sqrt(m[c] * m[c] + m[4 + c] * m[4 + c] + m[8 + c] * m[8 + c]);
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) {
      const double dot = m[a] * m[b] + m[4 + a] * m[4 + b] + m[8 + a] * m[8 + b];
      if (std::abs(dot) > 1e-9 * len[a] * len[b]) return 0;
    }
  if (std::abs(len[0] - len[1]) > 1e-9 * len[0] || std::abs(len[0] - len[2]) > 1e-9 * len[0])
    return 0;
  return len[0];
}

double SceneDescription::animationSpan() const {
  double span = 0;
  for (const SceneObject& o : objects)
    if (o.animation)
      span = std::max(
          span, o.animation->period > 0 ? o.animation->period : o.animation->keys.back().time);
  return span > 0 ? span : 1.0;
}

const SceneMaterial* SceneDescription::findMaterial(const std::string& name) const {
  for (const auto& [key, material] : materials)
    if (key == name) return &material;
  return nullptr;
}

Result<SceneDescription> parseSceneDescription(const std::string& text, const std::string& path) {
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return makeError(ErrorCode::kInvalidArgument, path, ": not valid JSON");
  Status status = Status::ok();
  Fields f(path, status);
  SceneDescription scene;
  scene.path = path;
  const std::filesystem::path base = std::filesystem::path(path).parent_path();
  f.onlyKeys(j, "scene", {"grid", "materials", "objects", "lights", "camera"});
  if (j.is_object() && j.contains("grid")) {
    const json& g = j["grid"];
    f.onlyKeys(g, "grid", {"resolution", "brick", "axis"});
    if (f.ok() && g.contains("resolution"))
      scene.grid.resolution = uint32_t(f.number(g["resolution"], "grid.resolution", 2, 65536));
    if (f.ok() && g.contains("brick")) {
      const double n = f.number(g["brick"], "grid.brick", 4, 32);
      if (!format::isValidBrickSize(uint32_t(n)) || n != std::floor(n))
        f.fail("grid.brick", "expected 4, 8, 16 or 32");
      scene.grid.brickSize = uint32_t(n);
    }
    if (f.ok() && g.contains("axis")) {
      const std::string axis = f.string(g["axis"], "grid.axis");
      if (axis == "x")
        scene.grid.axis = format::Axis::kX;
      else if (axis == "y")
        scene.grid.axis = format::Axis::kY;
      else if (axis == "z")
        scene.grid.axis = format::Axis::kZ;
      else
        f.fail("grid.axis", "\"" + axis + "\" is not x, y or z");
    }
  }
  if (f.ok() && j.contains("materials")) {
    if (!j["materials"].is_object()) f.fail("materials", "expected an object of named materials");
    for (const auto& [name, m] : j["materials"].items()) {
      if (!f.ok()) break;
      SceneMaterial material = readMaterial(m, "materials." + name, f);
      material.material.name = name;
      scene.materials.emplace_back(name, material);
    }
  }
  if (f.ok() && (!j.contains("objects") || !j["objects"].is_array()))
    f.fail("objects", "expected an array of objects");
  if (f.ok()) {
    for (size_t i = 0; i < j["objects"].size() && f.ok(); ++i)
      scene.objects.push_back(
          readObject(j["objects"][i], "objects[" + std::to_string(i) + "]", base, scene, f));
  }
  int volumes = 0;
  for (const SceneObject& o : scene.objects) volumes += o.kind == ObjectKind::kVolume;
  if (f.ok() && volumes > 1)
    f.fail("objects", "at most one volume per scene (the scene grid is the volume's grid)");
  if (f.ok() && j.contains("lights")) {
    if (!j["lights"].is_array()) f.fail("lights", "expected an array");
    for (size_t i = 0; f.ok() && i < j["lights"].size(); ++i) {
      const std::string where = "lights[" + std::to_string(i) + "]";
      const json& l = j["lights"][i];
      f.onlyKeys(l, where, {"position", "color", "intensity"});
      if (!f.ok()) break;
      Light light;
      if (!l.contains("position"))
        f.fail(where, "needs a \"position\"");
      else
        light.position = f.vector<3>(l["position"], where + ".position", -1e12, 1e12);
      if (l.contains("color")) light.color = f.vector<3>(l["color"], where + ".color", 0, 1e6);
      if (l.contains("intensity"))
        light.intensity = f.number(l["intensity"], where + ".intensity", 0, 1e12);
      scene.lights.push_back(light);
    }
  }
  if (f.ok() && j.contains("camera")) {
    const json& c = j["camera"];
    f.onlyKeys(c, "camera", {"azimuth", "elevation", "distance", "fov", "up"});
    if (f.ok() && c.contains("azimuth")) f.number(c["azimuth"], "camera.azimuth", -3600, 3600);
    if (f.ok() && c.contains("elevation")) f.number(c["elevation"], "camera.elevation", -90, 90);
    if (f.ok() && c.contains("distance")) f.number(c["distance"], "camera.distance", 1e-6, 1e6);
    if (f.ok() && c.contains("fov")) f.number(c["fov"], "camera.fov", 1, 179);
    if (f.ok() && c.contains("up")) {
      const std::string up = f.string(c["up"], "camera.up");
      if (f.ok() && up != "y" && up != "z" && up != "-y" && up != "-z")
        f.fail("camera.up", "\"" + up + "\" is not y, z, -y or -z");
    }
    scene.cameraJson = c.dump();
  }
  if (!status.isOk()) return status;
  return scene;
}

Result<SceneDescription> readSceneDescription(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    return makeError(ErrorCode::kIo, path, ": not a readable regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(ErrorCode::kIo, path, ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  if (!in.good() && !in.eof()) return makeError(ErrorCode::kIo, path, ": read failed");
  return parseSceneDescription(text.str(), path);
}

}  // namespace voxlink::scene
