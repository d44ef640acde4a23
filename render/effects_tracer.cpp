// SPDX-License-Identifier: BSD-3-Clause
#include "render/effects_tracer.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/detail/light_transport.h"
#include "render/detail/render_rows.h"
#include "render/render_model.h"

namespace voxlink::render {

namespace {

// One light as seen from a point: unit direction towards it, distance (infinite when
// directional) and radiance.
struct LightRay {
  glm::dvec3 toLight;
  double distance;
  glm::dvec3 radiance;
};

struct PendingRay {
  Ray ray;
  double weight;
  int depth;
  Medium medium;
};

}  // namespace

struct EffectsTracer::Frame {
  RenderSettings settings;
  std::vector<Light> lights;  // world; the frame's directional light when the settings have none
  bool shadows = false;
  double stopAt = 0;     // a ray ends once its transmittance is at or below this
  double minWeight = 0;  // spawned rays lighter than this are dropped
};

EffectsTracer::EffectsTracer(const SceneWalker& scene, const tf::TransferFunction& tf)
    : scene_(scene), tf_(tf) {}

EffectsTracer::Frame EffectsTracer::makeFrame(const Camera& camera,
                                              const RenderSettings& settings) const {
  Frame f;
  f.settings = settings;
  f.lights = settings.lights;
  if (f.lights.empty()) {
    const auto& l = settings.shading.lightDirection;
    const glm::dvec3 w =
        glm::normalize(camera.toWorld(glm::normalize(glm::dvec3(l[0], l[1], l[2]))));
    f.lights.push_back(Light{{w.x, w.y, w.z}, {1, 1, 1}, /*directional=*/true});
  }
  f.shadows = settings.shading.enabled && (settings.shading.shadows || settings.effects.shadows);
  f.stopAt = 1.0 - settings.terminationAlpha;
  f.minWeight = 1.0 - settings.terminationAlpha;
  return f;
}

Image EffectsTracer::render(const Camera& camera, const RenderSettings& settings) const {
  const Frame f = makeFrame(camera, settings);
  return renderRows(camera, settings, [&](const Ray& ray) { return trace(ray, f); });
}

std::array<double, 4> EffectsTracer::traceRay(const Ray& ray, const Camera& camera,
                                              const RenderSettings& settings) const {
  return trace(ray, makeFrame(camera, settings));
}

double EffectsTracer::shadowTransmittance(const glm::dvec3& point, const glm::dvec3& toLight,
                                          double lightDistance, const Frame& f) const {
  const double startOffset = scene_.shadowStartOffset();
  const Ray ray{point + toLight * startOffset, toLight};
  const double tMax = lightDistance - startOffset;
  double transmittance = 1.0;
  if (!(tMax > 0)) return transmittance;
  const auto materials = scene_.materials();
  const double stopAt = f.settings.shadowTerminationTransmittance;
  const double unit = scene_.opacityUnit();
  scene_.walk(ray, 0.0, tMax, [&](const SceneEvent& e) {
    if (e.kind == SceneEvent::Kind::kSurface)
      transmittance *= shadowTransmittanceOf(materials[e.material], f.settings.effects);
    else
      transmittance *= 1.0 - correctedAlpha(tf_.opacityAt(e.value), e.tEnd - e.t, unit);
    return transmittance >= stopAt;
  });
  return transmittance;
}

std::array<double, 4> EffectsTracer::trace(const Ray& primary, const Frame& f) const {
  const auto materials = scene_.materials();
  const Shading& shading = f.settings.shading;
  const Effects& effects = f.settings.effects;
  const double unit = scene_.opacityUnit();
  const double offset = scene_.surfaceOffset();
  const Box box = scene_.bounds();
  glm::dvec3 color(0.0);
  double background = 0.0;  // share of the pixel that reached the background

  auto lightAt = [&](const Light& l, const glm::dvec3& p) {
    const glm::dvec3 pos(l.position[0], l.position[1], l.position[2]);
    const glm::dvec3 rad(l.radiance[0], l.radiance[1], l.radiance[2]);
    if (l.directional) return LightRay{pos, HUGE_VAL, rad};
    const glm::dvec3 v = pos - p;
    const double dist = glm::length(v);
    return LightRay{dist > 0 ? v / dist : glm::dvec3(0.0), dist, rad};
  };

  // Ambient plus every light's lit terms, each times its shadow ray's transmittance. A surface's
  // shadow rays start `offset` off it along its faced normal n; a volume sample's at the sample.
  auto shadeSurfaceAt = [&](const format::MaterialRecord& m, const glm::dvec3& n,
                            const glm::dvec3& p, const glm::dvec3& toEye) {
    const glm::dvec3 c(m.color[0], m.color[1], m.color[2]);
    glm::dvec3 sum(0.0);
    bool first = true;
    for (const Light& light : f.lights) {
      const LightRay l = lightAt(light, p);
      const ShadedTerms s = shadeSurface(c, m.specular, m.shininess, n, l.toLight, toEye, shading);
      if (first) sum += s.ambient;
      first = false;
      double shadow = 1.0;
      if (f.shadows && glm::dot(n, l.toLight) > 0) {
        const glm::dvec3 from = p + n * offset;
        shadow = shadowTransmittance(from, l.toLight, lightAt(light, from).distance, f);
      }
      sum += shadow * s.lit * l.radiance;
    }
    return sum;
  };
  auto shadeVolumeAt = [&](const glm::dvec3& rgb, const glm::dvec3& gradient, const glm::dvec3& p,
                           const glm::dvec3& toEye) {
    glm::dvec3 sum(0.0);
    bool first = true;
    for (const Light& light : f.lights) {
      const LightRay l = lightAt(light, p);
      const ShadedTerms s = shadeSample(rgb, 1.0, gradient, l.toLight, toEye, shading);
      if (first) sum += s.ambient;
      first = false;
      const double shadow = f.shadows ? shadowTransmittance(p, l.toLight, l.distance, f) : 1.0;
      sum += shadow * s.lit * l.radiance;
    }
    return sum;
  };

  // Rays of the pixel still to trace, newest first; the order does not change the sum.
  std::vector<PendingRay> pending{{primary, 1.0, 0, Medium::kUnknown}};
  while (!pending.empty()) {
    const PendingRay r = pending.back();
    pending.pop_back();
    const glm::dvec3 d = r.ray.direction, toEye = -d;
    double transmittance = 1.0;
    auto spawn = [&](const glm::dvec3& origin, const glm::dvec3& dir, double share, Medium medium) {
      const double w = r.weight * transmittance * share;
      if (r.depth < effects.maxBounces && w > f.minWeight)
        pending.push_back({Ray{origin, dir}, w, r.depth + 1, medium});
    };
    auto [t0, t1] = intersectBox(r.ray.origin, d, box.lo, box.hi);
    t0 = std::max(t0, 0.0);
    if (t0 < t1) {
      scene_.walk(r.ray, t0, t1, [&](const SceneEvent& e) {
        if (e.kind == SceneEvent::Kind::kSurface) {
          const format::MaterialRecord& m = materials[e.material];
          const glm::dvec3 p = r.ray.origin + e.t * d;
          const glm::dvec3 nf = glm::dot(e.normal, toEye) < 0 ? -e.normal : e.normal;
          HitShares shares = splitHit(m, effects);
          std::optional<glm::dvec3> refracted;
          const bool entering = entersSurface(r.medium, d, e.normal);
          if (shares.refract > 0) {
            refracted = refractDirection(d, e.normal, m.refractiveIndex, entering);
            if (!refracted) {  // total internal reflection: the refracted share is mirrored
              shares.reflect += shares.refract;
              shares.refract = 0;
            }
          }
          const glm::dvec3 emission(m.emission[0], m.emission[1], m.emission[2]);
          glm::dvec3 local = emission * double(m.opacity);
          if (shares.local > 0) local += shares.local * shadeSurfaceAt(m, nf, p, toEye);
          color += r.weight * transmittance * local;
          if (shares.reflect > 0)
            spawn(p + nf * offset, reflectDirection(d, nf), shares.reflect, r.medium);
          if (shares.refract > 0)
            spawn(p - nf * offset, *refracted, shares.refract,
                  entering ? Medium::kInside : Medium::kOutside);
          transmittance *= shares.through;
        } else {
          const double a = correctedAlpha(tf_.opacityAt(e.value), e.tEnd - e.t, unit);
          if (a > 0) {
            const auto rgb = tf_.colorAt(e.value);
            const glm::dvec3 p = r.ray.origin + 0.5 * (e.t + e.tEnd) * d;
            color += r.weight * transmittance * a *
                     shadeVolumeAt({rgb[0], rgb[1], rgb[2]}, e.gradient, p, toEye);
            transmittance *= 1.0 - a;
          }
        }
        return transmittance > f.stopAt;
      });
    }
    background += r.weight * transmittance;
  }
  const auto& bg = f.settings.background;
  return {color.r + background * bg[0], color.g + background * bg[1], color.b + background * bg[2],
          1.0 - background};
}

}  // namespace voxlink::render
