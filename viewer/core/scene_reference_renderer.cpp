#include "viewer/core/scene_reference_renderer.h"

#include <algorithm>
#include <cmath>

#include "format/gradient_codec.h"
#include "viewer/core/render_model.h"
#include "viewer/core/render_rows.h"

namespace voxlink::viewer {

struct SceneReferenceRenderer::Frame {
  RenderSettings settings;
  glm::dvec3 toLight;  // world, unit
  double unit;         // smallest spacing
  Box box;
};

struct SceneReferenceRenderer::Hit {
  double t = HUGE_VAL;
  uint32_t sphere = 0;
  glm::dvec3 centre{0.0};  // index space
};

namespace {

glm::dvec3 decoded(uint16_t code) {
  const auto v = format::decodeGradient(code);
  return {v[0], v[1], v[2]};
}

}  // namespace

SceneReferenceRenderer::SceneReferenceRenderer(const format::VoxLinkFile& file,
                                               const format::TransferFunction& tf)
    : file_(file), tf_(tf), locator_(file), index_(file) {
  const format::FileHeader& h = file.header();
  for (int a = 0; a < 3; ++a) {
    dims_[a] = h.dims[a];
    origin_[a] = h.origin[a];
    spacing_[a] = h.spacing[a];
  }
}

glm::dvec3 SceneReferenceRenderer::toIndex(const glm::dvec3& w) const {
  return (w - origin_) / spacing_ + 0.5;
}
glm::dvec3 SceneReferenceRenderer::toWorld(const glm::dvec3& i) const {
  return origin_ + (i - 0.5) * spacing_;
}
glm::dvec3 SceneReferenceRenderer::dirToIndex(const glm::dvec3& d) const { return d / spacing_; }

SceneReferenceRenderer::Frame SceneReferenceRenderer::makeFrame(
    const Camera& camera, const RenderSettings& settings) const {
  Frame f;
  f.settings = settings;
  const auto& l = settings.shading.lightDirection;
  f.toLight = glm::normalize(camera.toWorld(glm::normalize(glm::dvec3(l[0], l[1], l[2]))));
  f.unit = std::min({spacing_.x, spacing_.y, spacing_.z});
  for (int a = 0; a < 3; ++a) {
    f.box.lo[a] = origin_[a] - 0.5 * spacing_[a];
    f.box.hi[a] = origin_[a] + (double(dims_[a]) - 0.5) * spacing_[a];
  }
  return f;
}

Image SceneReferenceRenderer::render(const Camera& camera, const RenderSettings& settings) const {
  const Frame f = makeFrame(camera, settings);
  return renderRows(camera, settings, [&](const Ray& ray) { return trace(ray, f); });
}

std::array<double, 4> SceneReferenceRenderer::traceRay(const Ray& ray, const Camera& camera,
                                                       const RenderSettings& settings) const {
  return trace(ray, makeFrame(camera, settings));
}

// Nearest t >= max(ta, 0) of the voxel's spheres inside its chord [ta, tz).
bool SceneReferenceRenderer::firstSphereHit(uint64_t voxel, const glm::dvec3& o,
                                            const glm::dvec3& d, double ta, double tz,
                                            Hit& hit) const {
  const auto [begin, end] = index_.sphereRefs(voxel);
  const auto refs = file_.sphereRefs();
  const auto spheres = file_.spheres();
  hit = Hit{};
  for (uint32_t r = begin; r < end; ++r) {
    const format::SphereRecord& s = spheres[refs[r]];
    const glm::dvec3 centre = toIndex({s.center[0], s.center[1], s.center[2]});
    const double radius = s.radius / spacing_.x;
    const glm::dvec3 oc = o - centre;
    const double a = glm::dot(d, d), halfB = glm::dot(oc, d),
                 c = glm::dot(oc, oc) - radius * radius;
    const double disc = halfB * halfB - a * c;
    if (disc < 0) continue;
    const double root = std::sqrt(disc), tMin = std::max(ta, 0.0);
    const double tNear = (-halfB - root) / a, tFar = (-halfB + root) / a;
    const double t = tNear >= tMin ? tNear : (tFar >= tMin ? tFar : HUGE_VAL);
    if (t >= ta && t < tz && t < hit.t) hit = Hit{t, refs[r], centre};
  }
  return hit.t < HUGE_VAL;
}

double SceneReferenceRenderer::geometryTransmittance(uint64_t voxel, const glm::dvec3& o,
                                                     const glm::dvec3& d, double ta,
                                                     double tz) const {
  double transmittance = 1.0;
  const uint32_t word = index_.surfaceWord(voxel);
  const auto materials = file_.materials();
  if (word != format::kNoSurface)
    transmittance *= 1.0 - materials[format::surfaceMaterial(word)].opacity;
  Hit hit;
  if (firstSphereHit(voxel, o, d, ta, tz, hit))
    transmittance *= 1.0 - materials[file_.spheres()[hit.sphere].material].opacity;
  return transmittance;
}

double SceneReferenceRenderer::shadowTransmittance(const glm::dvec3& worldPoint,
                                                   const Frame& f) const {
  const glm::dvec3 start = worldPoint + f.toLight * f.unit;
  auto [t0, t1] = intersectBox(start, f.toLight, f.box.lo, f.box.hi);
  t0 = std::max(t0, 0.0);
  double transmittance = 1.0;
  if (!(t0 < t1)) return transmittance;
  const double stopAt = f.settings.shadowTerminationTransmittance;
  const glm::dvec3 o = toIndex(start), d = dirToIndex(f.toLight);
  walkVoxels(o, d, t0, t1, dims_, [&](const glm::ivec3& c, double ta, double tb) {
    const int64_t i = locator_.find(uint32_t(c.x), uint32_t(c.y), uint32_t(c.z));
    if (i < 0) return true;
    if (file_.isScene()) transmittance *= geometryTransmittance(uint64_t(i), o, d, ta, tb);
    const int64_t slot = index_.volumeSlot(uint64_t(i));
    if (slot >= 0)
      transmittance *=
          1.0 - correctedAlpha(tf_.opacityAt(file_.value(uint64_t(slot))), tb - ta, f.unit);
    return transmittance >= stopAt;
  });
  return transmittance;
}

void SceneReferenceRenderer::compositeSurface(const format::MaterialRecord& m, glm::dvec3 n,
                                              const glm::dvec3& indexPoint, const glm::dvec3& toEye,
                                              const Frame& f, glm::dvec3& color,
                                              double& transmittance) const {
  if (glm::dot(n, toEye) < 0) n = -n;  // fragments are two-sided
  const glm::dvec3 c(m.color[0], m.color[1], m.color[2]);
  const ShadedTerms s =
      shadeSurface(c, m.specular, m.shininess, n, f.toLight, toEye, f.settings.shading);
  double shadow = 1.0;
  if (f.settings.shading.shadows && f.settings.shading.enabled && glm::dot(n, f.toLight) > 0)
    shadow = shadowTransmittance(toWorld(indexPoint) + n * (kSurfaceShadowBias * f.unit), f);
  const glm::dvec3 emission(m.emission[0], m.emission[1], m.emission[2]);
  color += transmittance * double(m.opacity) * (s.ambient + shadow * s.lit + emission);
  transmittance *= 1.0 - m.opacity;
}

std::array<double, 4> SceneReferenceRenderer::trace(const Ray& ray, const Frame& f) const {
  glm::dvec3 color(0.0);
  double transmittance = 1.0;
  auto [t0, t1] = intersectBox(ray.origin, ray.direction, f.box.lo, f.box.hi);
  t0 = std::max(t0, 0.0);
  const glm::dvec3 o = toIndex(ray.origin), d = dirToIndex(ray.direction);
  const glm::dvec3 toEye = -ray.direction;
  const double stopAt = 1.0 - f.settings.terminationAlpha;
  const auto materials = file_.materials();
  walkVoxels(o, d, t0, t1, dims_, [&](const glm::ivec3& c, double ta, double tb) {
    const int64_t found = locator_.find(uint32_t(c.x), uint32_t(c.y), uint32_t(c.z));
    if (found < 0) return true;
    const uint64_t i = uint64_t(found);
    if (file_.isScene()) {
      const uint32_t word = index_.surfaceWord(i);
      if (word != format::kNoSurface)
        compositeSurface(materials[format::surfaceMaterial(word)],
                         decoded(format::surfaceNormal(word)), o + ta * d, toEye, f, color,
                         transmittance);
      Hit hit;
      if (transmittance > stopAt && firstSphereHit(i, o, d, ta, tb, hit)) {
        const glm::dvec3 p = o + hit.t * d;
        compositeSurface(materials[file_.spheres()[hit.sphere].material],
                         glm::normalize(p - hit.centre), p, toEye, f, color, transmittance);
      }
      if (transmittance <= stopAt) return false;
    }
    const int64_t slot = index_.volumeSlot(i);
    if (slot < 0) return true;
    const double v = file_.value(uint64_t(slot));
    const double a = correctedAlpha(tf_.opacityAt(v), tb - ta, f.unit);
    if (a > 0) {
      const auto rgb = tf_.colorAt(v);
      const ShadedTerms s =
          shadeSample({rgb[0], rgb[1], rgb[2]}, 1.0, decoded(file_.gradientCodes()[uint64_t(slot)]),
                      f.toLight, toEye, f.settings.shading);
      double shadow = 1.0;
      if (f.settings.shading.shadows && f.settings.shading.enabled)
        shadow = shadowTransmittance(toWorld(o + 0.5 * (ta + tb) * d), f);
      color += transmittance * a * (s.ambient + shadow * s.lit);
      transmittance *= 1.0 - a;
    }
    return transmittance > stopAt;
  });
  const auto& bg = f.settings.background;
  return {color.r + transmittance * bg[0], color.g + transmittance * bg[1],
          color.b + transmittance * bg[2], 1.0 - transmittance};
}

}  // namespace voxlink::viewer
