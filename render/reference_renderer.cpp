// SPDX-License-Identifier: BSD-3-Clause
#include "render/reference_renderer.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "render/detail/render_rows.h"
#include "render/render_model.h"
#include "render/voxel_shadow_cache.h"

namespace voxlink::render {

struct ReferenceRenderer::Frame {
  RenderSettings settings;
  glm::dvec3 toLight;  // world, unit
  double unit;         // smallest spacing: the length the TF's opacities refer to
  double step;         // trilinear step, world units
  Box box;
  bool perVoxelShadows;                           // ShadowRays::kPerVoxel with shadows on
  std::shared_ptr<VoxelShadowCache> shadowCache;  // per frame; null: computed per request
};

ReferenceRenderer::ReferenceRenderer(const DenseVolume& volume, const tf::TransferFunction& tf)
    : volume_(volume), tf_(tf) {}

glm::dvec3 ReferenceRenderer::toIndex(const glm::dvec3& w) const {
  glm::dvec3 r;
  for (int a = 0; a < 3; ++a) r[a] = (w[a] - volume_.origin[a]) / volume_.spacing[a] + 0.5;
  return r;
}

glm::dvec3 ReferenceRenderer::dirToIndex(const glm::dvec3& d) const {
  return {d.x / volume_.spacing[0], d.y / volume_.spacing[1], d.z / volume_.spacing[2]};
}

ReferenceRenderer::Frame ReferenceRenderer::makeFrame(const Camera& camera,
                                                      const RenderSettings& settings) const {
  Frame f;
  f.settings = settings;
  const auto& l = settings.shading.lightDirection;
  f.toLight = glm::normalize(camera.toWorld(glm::normalize(glm::dvec3(l[0], l[1], l[2]))));
  f.unit = volume_.minSpacing();
  f.step = settings.stepVoxels * f.unit;
  f.box = volume_.worldBox();
  f.perVoxelShadows = settings.shading.enabled && settings.shading.shadows &&
                      settings.shading.shadowRays == ShadowRays::kPerVoxel;
  return f;
}

Image ReferenceRenderer::render(const Camera& camera, const RenderSettings& settings) const {
  Frame f = makeFrame(camera, settings);
  if (f.perVoxelShadows) f.shadowCache = std::make_shared<VoxelShadowCache>(volume_.voxelCount());
  return renderRows(camera, settings, [&](const Ray& ray) { return trace(ray, f); });
}

std::array<double, 4> ReferenceRenderer::tracePixel(const Camera& camera,
                                                    const RenderSettings& settings, uint32_t px,
                                                    uint32_t py) const {
  return trace(camera.primaryRay(px, py, settings.width, settings.height),
               makeFrame(camera, settings));
}

std::array<double, 4> ReferenceRenderer::traceRay(const Ray& ray, const Camera& camera,
                                                  const RenderSettings& settings) const {
  return trace(ray, makeFrame(camera, settings));
}

std::array<double, 4> ReferenceRenderer::trace(const Ray& ray, const Frame& f) const {
  glm::dvec3 color(0.0);
  double transmittance = 1.0;
  auto [t0, t1] = intersectBox(ray.origin, ray.direction, f.box.lo, f.box.hi);
  t0 = std::max(t0, 0.0);
  if (t0 < t1) {
    const glm::dvec3 o = toIndex(ray.origin), d = dirToIndex(ray.direction);
    if (f.settings.sampling == Sampling::kVoxel)
      traceVoxels(o, d, t0, t1, f, color, transmittance);
    else
      traceTrilinear(o, d, t0, t1, f, color, transmittance);
  }
  const auto& bg = f.settings.background;
  return {color.r + transmittance * bg[0], color.g + transmittance * bg[1],
          color.b + transmittance * bg[2], 1.0 - transmittance};
}

void ReferenceRenderer::traceVoxels(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
                                    const Frame& f, glm::dvec3& color,
                                    double& transmittance) const {
  const glm::dvec3 toEye =
      -(glm::dvec3(d.x * volume_.spacing[0], d.y * volume_.spacing[1], d.z * volume_.spacing[2]));
  const double stopAt = 1.0 - f.settings.terminationAlpha;
  walkVoxels(o, d, t0, t1, volume_.dims, [&](const glm::ivec3& c, double ta, double tb) {
    const double v = volume_.at(c.x, c.y, c.z);
    const double a = correctedAlpha(tf_.opacityAt(v), tb - ta, f.unit);
    if (a > 0) {
      const auto rgb = tf_.colorAt(v);
      const ShadedTerms s = shadeSample({rgb[0], rgb[1], rgb[2]}, 1.0,
                                        gradientDirection(volume_.gradient(c.x, c.y, c.z)),
                                        f.toLight, toEye, f.settings.shading);
      double shadow = 1.0;
      if (f.perVoxelShadows) {
        shadow = centreShadow(c, f);
      } else if (f.settings.shading.shadows && f.settings.shading.enabled) {
        const double tm = 0.5 * (ta + tb);
        glm::dvec3 world;
        for (int i = 0; i < 3; ++i)
          world[i] = volume_.origin[i] + (o[i] + tm * d[i] - 0.5) * volume_.spacing[i];
        shadow = shadowTransmittance(world, f);
      }
      color += transmittance * a * (s.ambient + shadow * s.lit);
      transmittance *= 1.0 - a;
    }
    return transmittance > stopAt;
  });
}

void ReferenceRenderer::traceTrilinear(const glm::dvec3& o, const glm::dvec3& d, double t0,
                                       double t1, const Frame& f, glm::dvec3& color,
                                       double& transmittance) const {
  const glm::dvec3 toEye =
      -(glm::dvec3(d.x * volume_.spacing[0], d.y * volume_.spacing[1], d.z * volume_.spacing[2]));
  const double stopAt = 1.0 - f.settings.terminationAlpha;
  // Classified corners of the current cell (colour and gradient direction weighted by opacity),
  // reused while samples stay in it.
  struct Corner {
    double alpha = 0;
    glm::dvec3 color{0.0}, gradient{0.0};
    double shadowedAlpha = 0;  // per-voxel shadows: alpha times its centre's transmittance
  };
  Corner corners[8];
  glm::ivec3 cached(INT32_MIN);
  for (int64_t k = 0;; ++k) {
    const double t = t0 + (double(k) + 0.5) * f.step;
    if (!(t < t1)) break;
    const glm::dvec3 q = o + t * d - 0.5;  // voxel centres at integers
    const glm::dvec3 fl = glm::floor(q);
    const glm::ivec3 c(fl);
    const glm::dvec3 w = q - fl;
    if (c != cached) {
      cached = c;
      for (int i = 0; i < 8; ++i) {
        const glm::ivec3 p = c + glm::ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
        corners[i] = Corner{};
        if (p.x < 0 || p.y < 0 || p.z < 0 || p.x >= int(volume_.dims[0]) ||
            p.y >= int(volume_.dims[1]) || p.z >= int(volume_.dims[2]))
          continue;
        const double v = volume_.at(p.x, p.y, p.z);
        const double a = tf_.opacityAt(v);
        if (!(a > 0)) continue;
        const auto rgb = tf_.colorAt(v);
        corners[i] = Corner{a, a * glm::dvec3(rgb[0], rgb[1], rgb[2]),
                            a * gradientDirection(volume_.gradient(p.x, p.y, p.z)),
                            f.perVoxelShadows ? a * centreShadow(p, f) : 0.0};
      }
    }
    double alpha = 0, shadowedAlpha = 0;
    glm::dvec3 premultiplied(0.0), gradient(0.0);
    for (int i = 0; i < 8; ++i) {
      const double wi =
          ((i & 1) ? w.x : 1 - w.x) * ((i & 2) ? w.y : 1 - w.y) * ((i & 4) ? w.z : 1 - w.z);
      alpha += wi * corners[i].alpha;
      premultiplied += wi * corners[i].color;
      gradient += wi * corners[i].gradient;
      shadowedAlpha += wi * corners[i].shadowedAlpha;
    }
    if (!(alpha > 0)) continue;
    const ShadedTerms s =
        shadeSample(premultiplied, alpha, gradient, f.toLight, toEye, f.settings.shading);
    const double a = correctedAlpha(alpha, f.step, f.unit);
    double shadow = 1.0;
    if (f.perVoxelShadows) {
      // The corners' centre transmittances weighted by trilinear weight times alpha.
      shadow = std::clamp(shadowedAlpha / alpha, 0.0, 1.0);
    } else if (f.settings.shading.shadows && f.settings.shading.enabled) {
      glm::dvec3 world;
      for (int i = 0; i < 3; ++i) world[i] = volume_.origin[i] + q[i] * volume_.spacing[i];
      shadow = shadowTransmittance(world, f);
    }
    color += transmittance * (a / alpha) * (s.ambient + shadow * s.lit);
    transmittance *= 1.0 - a;
    if (transmittance <= stopAt) break;
  }
}

double ReferenceRenderer::shadowTransmittance(const glm::dvec3& worldPoint, const Frame& f) const {
  const glm::dvec3 start = worldPoint + f.toLight * f.unit;
  auto [t0, t1] = intersectBox(start, f.toLight, f.box.lo, f.box.hi);
  t0 = std::max(t0, 0.0);
  double transmittance = 1.0;
  if (!(t0 < t1)) return transmittance;
  const double stopAt = f.settings.shadowTerminationTransmittance;
  walkVoxels(toIndex(start), dirToIndex(f.toLight), t0, t1, volume_.dims,
             [&](const glm::ivec3& c, double ta, double tb) {
               transmittance *=
                   1.0 - correctedAlpha(tf_.opacityAt(volume_.at(c.x, c.y, c.z)), tb - ta, f.unit);
               return transmittance >= stopAt;
             });
  return transmittance;
}

double ReferenceRenderer::centreShadow(const glm::ivec3& c, const Frame& f) const {
  auto compute = [&] {
    glm::dvec3 world;
    for (int i = 0; i < 3; ++i) world[i] = volume_.origin[i] + double(c[i]) * volume_.spacing[i];
    return shadowTransmittance(world, f);
  };
  if (!f.shadowCache) return compute();
  return f.shadowCache->get(volume_.index(uint32_t(c.x), uint32_t(c.y), uint32_t(c.z)), compute);
}

}  // namespace voxlink::render
