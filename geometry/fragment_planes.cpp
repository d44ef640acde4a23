// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/fragment_planes.h"

#include <algorithm>
#include <cmath>

#include "base/parallel_for.h"

namespace voxlink::geometry {
namespace {

using Vec3 = std::array<double, 3>;

// How far (voxels) a piece's point must lie behind another plane for the crease to count as
// convex: coplanar pieces (a material border) are not clipped by each other.
constexpr double kConvexMargin = 1e-3;

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double length(const Vec3& a) { return std::sqrt(dot(a, a)); }

// The part of a triangle inside the box [lo, lo + 1]^3 (Sutherland-Hodgman, closed half-spaces):
// its area and the centroid of that area (the mean of its corners when the area is zero, as for
// a triangle that only touches the box).
struct Clipped {
  double area = 0;
  Vec3 centroid{0, 0, 0};
  bool empty = true;                    // the triangle misses the box
  Vec3 boxLo{1, 1, 1}, boxHi{0, 0, 0};  // the part's bounds, voxel-local
};

Clipped clipToVoxel(const Vec3 (&corner)[3], const Vec3& lo) {
  std::vector<Vec3> poly(corner, corner + 3), next;
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const double bound = lo[axis] + side;
      auto inside = [&](const Vec3& p) { return side == 0 ? p[axis] >= bound : p[axis] <= bound; };
      next.clear();
      for (size_t i = 0; i < poly.size(); ++i) {
        const Vec3& a = poly[i];
        const Vec3& b = poly[(i + 1) % poly.size()];
        if (inside(a)) next.push_back(a);
        if (inside(a) != inside(b)) {
          const double s = (bound - a[axis]) / (b[axis] - a[axis]);
          Vec3 p{a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])};
          p[axis] = bound;
          next.push_back(p);
        }
      }
      poly.swap(next);
      if (poly.empty()) return {};
    }
  }
  Clipped c;
  c.empty = false;
  Vec3 weighted{0, 0, 0}, mean{0, 0, 0};
  for (size_t i = 0; i < poly.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      mean[a] += poly[i][a] / double(poly.size());
      c.boxLo[a] = std::min(c.boxLo[a], poly[i][a] - lo[a]);
      c.boxHi[a] = std::max(c.boxHi[a], poly[i][a] - lo[a]);
    }
  for (size_t i = 1; i + 1 < poly.size(); ++i) {
    const double area = 0.5 * length(cross(sub(poly[i], poly[0]), sub(poly[i + 1], poly[0])));
    c.area += area;
    for (int a = 0; a < 3; ++a)
      weighted[a] += area * (poly[0][a] + poly[i][a] + poly[i + 1][a]) / 3;
  }
  for (int a = 0; a < 3; ++a) c.centroid[a] = c.area > 0 ? weighted[a] / c.area : mean[a];
  return c;
}

struct Member {
  uint32_t pair;  // index into triangleIds
  Vec3 normal;    // unit
  Clipped part;
  uint16_t material;
};

struct Group {
  Vec3 seed, normalSum{0, 0, 0}, pointSum{0, 0, 0}, pointMean{0, 0, 0};
  double weight = 0;
  uint32_t members = 0;
  uint16_t material;
  Vec3 boxLo{1, 1, 1}, boxHi{0, 0, 0};  // bounds of the members' parts, voxel-local
};

}  // namespace

Result<PlaneFragments> buildPlaneFragments(const TriangleMesh& mesh, const VoxelGrid& grid,
                                           const SurfaceVoxelization& surface,
                                           double mergeAngleDegrees) {
  if (surface.triangleStart.size() != surface.voxels.size() + 1)
    return makeError(ErrorCode::kInvalidArgument,
                     "plane fragments: the voxelization kept no triangle lists");
  if (!(mergeAngleDegrees >= 0 && mergeAngleDegrees <= 180))
    return makeError(ErrorCode::kInvalidArgument, "plane fragments: merge angle ",
                     mergeAngleDegrees, " is not in [0, 180] degrees");
  const double cosLimit = std::cos(mergeAngleDegrees * (3.14159265358979323846 / 180.0));
  const size_t voxelCount = surface.voxels.size();
  // Per voxel its groups, built in parallel, then concatenated in voxel order.
  std::vector<std::vector<PlaneFragment>> perVoxel(voxelCount);
  PlaneFragments out;
  out.fragmentOfPair.assign(surface.triangleIds.size(), 0);
  base::parallelFor(voxelCount, 0, [&](uint64_t v) {
    const SurfaceVoxel& voxel = surface.voxels[v];
    const Vec3 lo{double(voxel.x), double(voxel.y), double(voxel.z)};
    std::vector<Member> members;
    for (uint32_t i = surface.triangleStart[v]; i < surface.triangleStart[v + 1]; ++i) {
      const uint32_t t = surface.triangleIds[i];
      Vec3 c[3];
      for (int k = 0; k < 3; ++k) {
        const float* p = &mesh.positions[3 * size_t(mesh.triangles[3 * size_t(t) + k])];
        c[k] = grid.toGrid(p[0], p[1], p[2]);
      }
      const Vec3 n = cross(sub(c[1], c[0]), sub(c[2], c[0]));
      const double len = length(n);
      if (!(len > 0)) continue;  // the voxelizer skips zero-area triangles already
      const uint16_t material = mesh.triangleMaterials.empty() ? 0 : mesh.triangleMaterials[t];
      members.push_back({i, {n[0] / len, n[1] / len, n[2] / len}, clipToVoxel(c, lo), material});
    }
    std::stable_sort(members.begin(), members.end(),
                     [](const Member& a, const Member& b) { return a.part.area > b.part.area; });
    std::vector<Group> groups;
    std::vector<uint32_t> groupOf(members.size());
    for (size_t m = 0; m < members.size(); ++m) {
      const Member& t = members[m];
      size_t g = 0;
      while (g < groups.size() &&
             !(groups[g].material == t.material && dot(groups[g].seed, t.normal) >= cosLimit))
        ++g;
      if (g == groups.size()) groups.push_back(Group{t.normal, {}, {}, {}, 0, 0, t.material});
      Group& group = groups[g];
      // Weights: the area inside the voxel, plus a trace of the whole triangle so that a group
      // of triangles that only touch the voxel still has a normal and a point.
      const double w = t.part.area + 1e-9;
      for (int a = 0; a < 3; ++a) {
        group.normalSum[a] += w * t.normal[a];
        group.pointSum[a] += w * t.part.centroid[a];
      }
      group.weight += w;
      ++group.members;
      if (!t.part.empty)
        for (int a = 0; a < 3; ++a) {
          group.boxLo[a] = std::min(group.boxLo[a], t.part.boxLo[a]);
          group.boxHi[a] = std::max(group.boxHi[a], t.part.boxHi[a]);
        }
      groupOf[m] = uint32_t(g);
    }
    std::vector<PlaneFragment>& fragments = perVoxel[v];
    size_t largestGroup = 0;
    for (size_t g = 0; g < groups.size(); ++g)
      if (groups[g].weight > groups[largestGroup].weight) largestGroup = g;
    std::vector<uint32_t> fragmentOf(groups.size());
    for (size_t i = 0; i < groups.size(); ++i) {
      const Group& g = groups[i];
      if (g.weight < kMinFragmentArea && i != largestGroup) continue;
      fragmentOf[i] = uint32_t(fragments.size());
      const double len = length(g.normalSum);
      const Vec3 n = len > 1e-9 * g.weight
                         ? Vec3{g.normalSum[0] / len, g.normalSum[1] / len, g.normalSum[2] / len}
                         : g.seed;
      Vec3 p;
      for (int a = 0; a < 3; ++a) p[a] = g.pointSum[a] / g.weight - (lo[a] + 0.5);
      // The piece's box seen along the normal's largest axis; the whole voxel face when no
      // member reaches into the voxel.
      PlaneFragment fragment{n, p, g.material, 0, {0, 0}, {1, 1}};
      for (int a = 1; a < 3; ++a)
        if (std::abs(n[a]) > std::abs(n[fragment.extentAxis])) fragment.extentAxis = a;
      if (g.boxLo[0] <= g.boxHi[0])
        for (int k = 0; k < 2; ++k) {
          const int a = (fragment.extentAxis + 1 + k) % 3;
          fragment.extentLo[k] = g.boxLo[a];
          fragment.extentHi[k] = g.boxHi[a];
        }
      fragments.push_back(fragment);
    }
    // Convex creases: each piece's point behind the other's plane (by more than rounding).
    for (PlaneFragment& a : fragments) {
      a.convex = fragments.size() > 1;
      for (const PlaneFragment& b : fragments)
        if (&a != &b && !(dot(a.normal, sub(b.point, a.point)) < -kConvexMargin &&
                          dot(b.normal, sub(a.point, b.point)) < -kConvexMargin))
          a.convex = false;
    }
    for (size_t i = 0; i < groups.size(); ++i)
      if (groups[i].weight < kMinFragmentArea && i != largestGroup) fragmentOf[i] = kLeftOut;
    for (size_t m = 0; m < members.size(); ++m)
      out.fragmentOfPair[members[m].pair] = fragmentOf[groupOf[m]];
  });
  out.start.resize(voxelCount + 1, 0);
  for (size_t v = 0; v < voxelCount; ++v)
    out.start[v + 1] = out.start[v] + uint32_t(perVoxel[v].size());
  out.fragments.reserve(out.start[voxelCount]);
  for (size_t v = 0; v < voxelCount; ++v) {
    for (uint32_t i = surface.triangleStart[v]; i < surface.triangleStart[v + 1]; ++i)
      if (out.fragmentOfPair[i] != kLeftOut) out.fragmentOfPair[i] += out.start[v];
    out.fragments.insert(out.fragments.end(), perVoxel[v].begin(), perVoxel[v].end());
    std::vector<PlaneFragment>().swap(perVoxel[v]);
  }
  return out;
}

}  // namespace voxlink::geometry
