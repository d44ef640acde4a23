// SPDX-License-Identifier: BSD-3-Clause
// A SceneWalker over exact planes and spheres, for testing the ray-traced scene mode against
// optics worked out by hand. It also records every ray it is asked to walk.
#pragma once

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

#include "render/scene_walker.h"

namespace voxlink::render::testing {

struct AnalyticPlane {
  glm::dvec3 point, normal;  // unit normal; the plane is infinite unless halfSize > 0
  uint32_t material;
  double halfSize = 0;  // a square of this half side around `point` (axis-aligned planes only)
};

struct AnalyticSphere {
  glm::dvec3 centre;
  double radius;
  uint32_t material;
};

class AnalyticScene : public SceneWalker {
 public:
  std::vector<format::MaterialRecord> materialTable;
  std::vector<AnalyticPlane> planes;
  std::vector<AnalyticSphere> spheres;
  Box box{glm::dvec3(-100.0), glm::dvec3(100.0)};
  double offset = 1e-7;
  mutable std::vector<Ray> walked;  // every ray walk() was asked for, in order
  mutable std::mutex mutex;

  void walk(const Ray& ray, double tMin, double tMax,
            const std::function<bool(const SceneEvent&)>& visit) const override {
    {
      std::lock_guard<std::mutex> lock(mutex);
      walked.push_back(ray);
    }
    std::vector<SceneEvent> events;
    for (const AnalyticPlane& p : planes) {
      const double denom = glm::dot(ray.direction, p.normal);
      if (std::abs(denom) < 1e-15) continue;
      const double t = glm::dot(p.point - ray.origin, p.normal) / denom;
      if (p.halfSize > 0) {
        const glm::dvec3 q = ray.origin + t * ray.direction - p.point;
        if (std::abs(q.x) > p.halfSize || std::abs(q.y) > p.halfSize || std::abs(q.z) > p.halfSize)
          continue;
      }
      SceneEvent e;
      e.t = t;
      e.normal = p.normal;
      e.material = p.material;
      events.push_back(e);
    }
    for (const AnalyticSphere& s : spheres) {
      const glm::dvec3 oc = ray.origin - s.centre;
      const double b = glm::dot(oc, ray.direction), c = glm::dot(oc, oc) - s.radius * s.radius;
      const double disc = b * b - c;
      if (disc < 0) continue;
      for (double t : {-b - std::sqrt(disc), -b + std::sqrt(disc)}) {
        SceneEvent e;
        e.t = t;
        e.normal = glm::normalize(ray.origin + t * ray.direction - s.centre);
        e.material = s.material;
        events.push_back(e);
      }
    }
    std::sort(events.begin(), events.end(),
              [](const SceneEvent& a, const SceneEvent& b) { return a.t < b.t; });
    for (const SceneEvent& e : events)
      if (e.t >= tMin && e.t <= tMax && !visit(e)) return;
  }
  std::span<const format::MaterialRecord> materials() const override { return materialTable; }
  Box bounds() const override { return box; }
  double surfaceOffset() const override { return offset; }
  double shadowStartOffset() const override { return offset; }
  double opacityUnit() const override { return 1.0; }
};

// An opaque material: diffuse colour c, optional emission, mirror and glass shares.
inline format::MaterialRecord analyticMaterial(glm::dvec3 c, double emission = 0,
                                               double reflectivity = 0, double transmission = 0,
                                               double ior = 1, double opacity = 1) {
  format::MaterialRecord m{};
  for (int a = 0; a < 3; ++a) {
    m.color[a] = float(c[a]);
    m.emission[a] = float(emission);
  }
  m.opacity = float(opacity);
  m.reflectivity = float(reflectivity);
  m.transmission = float(transmission);
  m.refractiveIndex = float(ior);
  return m;
}

}  // namespace voxlink::render::testing
