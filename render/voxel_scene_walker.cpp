// SPDX-License-Identifier: BSD-3-Clause
#include "render/voxel_scene_walker.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "format/gradient_codec.h"
#include "render/render_model.h"

namespace voxlink::render {

namespace {

glm::dvec3 decoded(uint16_t code) {
  const auto v = format::decodeGradient(code);
  return {v[0], v[1], v[2]};
}

}  // namespace

VoxelSceneWalker::VoxelSceneWalker(const format::VoxLinkFile& file)
    : file_(file), locator_(file), index_(file) {
  const format::FileHeader& h = file.header();
  for (int a = 0; a < 3; ++a) {
    dims_[a] = h.dims[a];
    origin_[a] = h.origin[a];
    spacing_[a] = h.spacing[a];
    box_.lo[a] = origin_[a] - 0.5 * spacing_[a];
    box_.hi[a] = origin_[a] + (double(dims_[a]) - 0.5) * spacing_[a];
  }
  unit_ = std::min({spacing_.x, spacing_.y, spacing_.z});
  mode_ = file.isScene() ? file.surfaceMode() : format::SurfaceMode::kMean;
  for (const format::FragmentRecord& f : file.fragments()) {
    planeNormals_.push_back(glm::normalize(decoded(format::surfaceNormal(f.word))));
    planeExtents_.push_back(format::decodeExtent(f.extent));
  }
}

std::span<const format::MaterialRecord> VoxelSceneWalker::materials() const {
  const auto m = file_.materials();
  return {m.data(), m.size()};
}

// A voxel's single fragment stands for a surface anywhere in the voxel, so rays it spawns start
// voxels away; a plane or triangle hit lies on the stored surface (render_model.h).
double VoxelSceneWalker::surfaceOffset() const {
  switch (mode_) {
    case format::SurfaceMode::kMean:
      return kSurfaceShadowBias * unit_;
    case format::SurfaceMode::kPlanes:
      return kListSurfaceOffset * unit_;
    case format::SurfaceMode::kTriangles:
      break;
  }
  return kTriangleSurfaceOffset * unit_;
}

double VoxelSceneWalker::shadowStartOffset() const {
  return mode_ == format::SurfaceMode::kMean ? unit_ : surfaceOffset();
}

SceneEvent VoxelSceneWalker::listHit(const Ray& ray, const glm::ivec3& cell, uint32_t slot,
                                     double ta, double tb) const {
  SceneEvent hit;
  hit.t = HUGE_VAL;
  const auto starts = file_.fragmentStarts();
  if (mode_ == format::SurfaceMode::kPlanes) {
    const auto fragments = file_.fragments();
    const glm::dvec3 centre = origin_ + glm::dvec3(cell) * spacing_;
    // Signed distance of world point p in front of plane f.
    auto inFront = [&](uint32_t f, const glm::dvec3& p) {
      return glm::dot(planeNormals_[f], p - centre) -
             fragments[f].offset * format::kPlaneOffsetUnit * unit_;
    };
    for (uint32_t f = starts[slot]; f < starts[slot + 1]; ++f) {
      const glm::dvec3& n = planeNormals_[f];
      const double denominator = glm::dot(n, ray.direction);
      if (denominator == 0) continue;
      const double t = -inFront(f, ray.origin) / denominator;
      // The chord grown at both ends by kPlaneHitTolerance along the normal (never before the
      // ray's origin, t = 0, as in the GL ray tracer): where neighbouring planes part at their
      // shared face, a ray crossing the surface between them hits one of them. At most
      // kPlaneHitReach along the ray, so a plane seen edge-on (a silhouette) does not reach far out
      // of its voxel.
      const double grow = format::kPlaneHitTolerance * unit_ *
                          std::min(1 / std::abs(denominator), format::kPlaneHitReach);
      if (!(t >= std::max(ta - grow, 0.0) && t < tb + grow && t < hit.t)) continue;
      // The hit in voxel-local coordinates ([0, 1]^3 in the cell), against the piece's box and,
      // at a convex crease, behind the voxel's other planes.
      const glm::dvec3 p = ray.origin + t * ray.direction;
      const glm::dvec3 local = (p - centre) / spacing_ + 0.5;
      const format::FragmentExtent& extent = planeExtents_[f];
      bool inside = format::extentHolds(extent, {local.x, local.y, local.z});
      for (uint32_t g = starts[slot]; inside && extent.convex && g < starts[slot + 1]; ++g)
        if (g != f && inFront(g, p) > format::kConvexTolerance * unit_) inside = false;
      if (inside) {
        hit.t = t;
        hit.normal = n;
        hit.material = format::surfaceMaterial(fragments[f].word);
      }
    }
    return hit;
  }
  const auto refs = file_.triangleRefs();
  const auto triangles = file_.triangles();
  for (uint32_t r = starts[slot]; r < starts[slot + 1]; ++r) {
    const format::TriangleRecord& tri = triangles[refs[r]];
    const glm::dvec3 a(tri.vertices[0], tri.vertices[1], tri.vertices[2]);
    const glm::dvec3 e1 = glm::dvec3(tri.vertices[3], tri.vertices[4], tri.vertices[5]) - a;
    const glm::dvec3 e2 = glm::dvec3(tri.vertices[6], tri.vertices[7], tri.vertices[8]) - a;
    // Moller-Trumbore, double precision.
    const glm::dvec3 p = glm::cross(ray.direction, e2);
    const double det = glm::dot(e1, p);
    if (det == 0) continue;
    const glm::dvec3 s = ray.origin - a;
    const double u = glm::dot(s, p) / det;
    if (u < 0 || u > 1) continue;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(ray.direction, q) / det;
    if (v < 0 || u + v > 1) continue;
    const double t = glm::dot(e2, q) / det;
    if (t >= ta && t < tb && t < hit.t) {
      hit.t = t;
      hit.normal = glm::normalize(glm::cross(e1, e2));
      hit.material = tri.material;
    }
  }
  return hit;
}

void VoxelSceneWalker::walk(const Ray& ray, double tMin, double tMax,
                            const std::function<bool(const SceneEvent&)>& visit) const {
  auto [t0, t1] = intersectBox(ray.origin, ray.direction, box_.lo, box_.hi);
  t0 = std::max(t0, tMin);
  t1 = std::min(t1, tMax);
  if (!(t0 < t1)) return;
  // Index space: voxel i spans [i, i + 1); t stays the world distance along the unit ray.
  const glm::dvec3 o = (ray.origin - origin_) / spacing_ + 0.5;
  const glm::dvec3 d = ray.direction / spacing_;
  const bool scene = file_.isScene();
  const auto spheres = file_.spheres();
  const auto refs = file_.sphereRefs();
  walkVoxels(o, d, t0, t1, dims_, [&](const glm::ivec3& c, double ta, double tb) {
    const int64_t found = locator_.find(uint32_t(c.x), uint32_t(c.y), uint32_t(c.z));
    if (found < 0) return true;
    const uint64_t i = uint64_t(found);
    if (scene) {
      SceneEvent surfaceHit;
      surfaceHit.t = HUGE_VAL;
      if (mode_ == format::SurfaceMode::kMean) {
        const uint32_t word = index_.surfaceWord(i);
        if (word != format::kNoSurface) {
          SceneEvent e;
          e.t = ta;
          e.normal = glm::normalize(decoded(format::surfaceNormal(word)));
          e.material = format::surfaceMaterial(word);
          if (!visit(e)) return false;
        }
      } else if (index_.surface().has(i)) {
        surfaceHit = listHit(ray, c, index_.surface().slot(i), ta, tb);
      }
      // The nearest hit t >= max(ta, 0) of the voxel's spheres that lies inside its chord, so
      // each hit is met in exactly one voxel.
      const auto [begin, end] = index_.sphereRefs(i);
      SceneEvent hit;
      hit.t = HUGE_VAL;
      for (uint32_t r = begin; r < end; ++r) {
        const format::SphereRecord& s = spheres[refs[r]];
        const glm::dvec3 centre =
            (glm::dvec3(s.center[0], s.center[1], s.center[2]) - origin_) / spacing_ + 0.5;
        const double radius = s.radius / spacing_.x;
        // Closest-approach form of the discriminant, as the GL ray tracer computes it.
        const glm::dvec3 oc = o - centre;
        const double a = glm::dot(d, d), b = glm::dot(oc, d) / a;
        const glm::dvec3 perp = oc - b * d;
        const double disc = radius * radius - glm::dot(perp, perp);
        if (disc < 0) continue;
        const double root = std::sqrt(disc / a), tLow = std::max(ta, 0.0);
        const double tNear = -b - root, tFar = -b + root;
        const double t = tNear >= tLow ? tNear : (tFar >= tLow ? tFar : HUGE_VAL);
        if (t >= ta && t < tb && t < hit.t) {
          hit.t = t;
          hit.normal = glm::normalize(o + t * d - centre);
          hit.material = s.material;
        }
      }
      // Surface and sphere hits of one voxel, nearest first.
      if (hit.t < surfaceHit.t) std::swap(hit, surfaceHit);
      if (surfaceHit.t < HUGE_VAL && !visit(surfaceHit)) return false;
      if (hit.t < HUGE_VAL && !visit(hit)) return false;
    }
    const int64_t slot = index_.volumeSlot(i);
    if (slot < 0) return true;
    SceneEvent e;
    e.kind = SceneEvent::Kind::kVolume;
    e.t = ta;
    e.tEnd = tb;
    e.value = file_.value(uint64_t(slot));
    e.gradient = decoded(file_.gradientCodes()[uint64_t(slot)]);
    return visit(e);
  });
}

}  // namespace voxlink::render
