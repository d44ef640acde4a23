// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/detail/triangle_box_overlap.h"

#include <algorithm>
#include <cmath>

namespace voxlink::geometry {
namespace {

Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

bool triangleOverlapsVoxelSat(const Vec3d& a, const Vec3d& b, const Vec3d& c, int64_t i, int64_t j,
                              int64_t k) {
  const int64_t lo[3] = {i, j, k};
  // Box normals, with the tie rule (a voxel does not own its upper faces).
  for (int axis = 0; axis < 3; ++axis) {
    const double mn = std::min({a[axis], b[axis], c[axis]});
    const double mx = std::max({a[axis], b[axis], c[axis]});
    if (mn >= double(lo[axis] + 1) || mx < double(lo[axis])) return false;
  }
  const Vec3d centre = {i + 0.5, j + 0.5, k + 0.5};
  const double h = 0.5;
  const Vec3d v[3] = {sub(a, centre), sub(b, centre), sub(c, centre)};
  const Vec3d e[3] = {sub(v[1], v[0]), sub(v[2], v[1]), sub(v[0], v[2])};
  auto separated = [&](const Vec3d& axis) {
    const double p0 = dot(axis, v[0]), p1 = dot(axis, v[1]), p2 = dot(axis, v[2]);
    const double r = h * (std::abs(axis[0]) + std::abs(axis[1]) + std::abs(axis[2]));
    return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
  };
  // The 9 edge x box-edge axes.
  static constexpr Vec3d kUnit[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const Vec3d& edge : e)
    for (const Vec3d& unit : kUnit)
      if (separated(cross(edge, unit))) return false;
  // The triangle normal.
  return !separated(cross(e[0], e[1]));
}

TriangleVoxelTest::TriangleVoxelTest(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d v[3] = {a, b, c};
  const Vec3d e[3] = {sub(b, a), sub(c, b), sub(a, c)};
  n_ = cross(e[0], e[1]);
  offset_ = dot(n_, a);
  for (int axis = 0; axis < 3; ++axis) {
    min_[axis] = std::min({a[axis], b[axis], c[axis]});
    max_[axis] = std::max({a[axis], b[axis], c[axis]});
  }
  // Plane: the box corner furthest along n and the one furthest against it (box size 1).
  const Vec3d critical = {n_[0] > 0.0 ? 1.0 : 0.0, n_[1] > 0.0 ? 1.0 : 0.0,
                          n_[2] > 0.0 ? 1.0 : 0.0};
  d1_ = dot(n_, sub(critical, a));
  d2_ = dot(n_, sub({1.0 - critical[0], 1.0 - critical[1], 1.0 - critical[2]}, a));
  // Projections: axis 0 -> (y, z), 1 -> (z, x), 2 -> (x, y); inward edge normals of the projected
  // triangle, oriented by the sign of the normal's component along the dropped axis.
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    const double sign = n_[axis] < 0.0 ? -1.0 : 1.0;
    Edges& out = edges_[axis];
    for (int t = 0; t < 3; ++t) {
      const double nu = -e[t][w] * sign, nv = e[t][u] * sign;
      out.nu[t] = nu;
      out.nv[t] = nv;
      out.d[t] = -(nu * v[t][u] + nv * v[t][w]) + std::max(0.0, nu) + std::max(0.0, nv);
    }
  }
}

int64_t TriangleVoxelTest::firstVoxel(int axis) const {
  return static_cast<int64_t>(std::floor(min_[axis]));
}
int64_t TriangleVoxelTest::lastVoxel(int axis) const {
  return static_cast<int64_t>(std::floor(max_[axis]));
}

}  // namespace voxlink::geometry
