// SPDX-License-Identifier: BSD-3-Clause
// Exact triangle / voxel overlap in grid coordinates (voxel (i, j, k) is the box
// [i, i+1] x [j, j+1] x [k, k+1]; see voxel_grid.h), evaluated in double precision.
//
// Overlap is Akenine-Moller's separating-axis test (2001) with its 13 axes: the 3 box normals,
// the triangle normal and the 9 cross products of triangle edges with box edges, on the closed
// box (touching counts), plus one tie rule:
//   a voxel owns its lower faces, not its upper ones: a triangle whose extent along an axis
//   starts exactly at a voxel's upper face (min coordinate == i + 1) does not overlap it.
// So a triangle lying exactly on a voxel plane marks only the voxels above the plane (a wall on
// a plane is one voxel thick), and a surface that ends exactly on a plane also marks the voxel
// just above. Other exact touches (an edge grazing a box edge) count as overlap.
// Degenerate triangles: the 13-axis test stays exact for segments and points (zero axes never
// separate), but the surface voxelizer skips triangles of zero area (no normal; see
// surface_voxelizer.h).
#pragma once

#include <array>
#include <cstdint>

namespace voxlink::geometry {

using Vec3d = std::array<double, 3>;

// Reference form: the 13 axes one by one, plus the tie rule. Slow; used by the tests as the
// brute-force ground truth.
bool triangleOverlapsVoxelSat(const Vec3d& a, const Vec3d& b, const Vec3d& c, int64_t i, int64_t j,
                              int64_t k);

// Fast form for one triangle against many voxels (Schwarz & Seidel 2010: the same 13 axes as a
// plane test and three 2-D projection tests with precomputed edge functions). Same answers as
// triangleOverlapsVoxelSat for voxels inside the triangle's bounding box (callers iterate over
// it, which is the 3 box-normal axes).
class TriangleVoxelTest {
 public:
  TriangleVoxelTest(const Vec3d& a, const Vec3d& b, const Vec3d& c);

  const Vec3d& normal() const { return n_; }      // (b - a) x (c - a), not normalized
  double planeOffset() const { return offset_; }  // n . a: the plane is n . x = offset
  const Vec3d& min() const { return min_; }
  const Vec3d& max() const { return max_; }
  // Lowest / highest voxel index overlapped along `axis` (before clipping to a grid).
  int64_t firstVoxel(int axis) const;
  int64_t lastVoxel(int axis) const;

  // Projection test in the plane orthogonal to `axis` (0: yz, 1: zx, 2: xy) for the column of
  // voxels whose other two indices are (u, v) in (y, z), (z, x) or (x, y) order.
  bool projectionOverlaps(int axis, double u, double v) const {
    const Edges& e = edges_[axis];
    for (int t = 0; t < 3; ++t)
      if (e.nu[t] * u + e.nv[t] * v + e.d[t] < 0.0) return false;
    return true;
  }
  bool planeOverlaps(double x, double y, double z) const {
    const double np = n_[0] * x + n_[1] * y + n_[2] * z;
    return (np + d1_) * (np + d2_) <= 0.0;
  }
  // Voxel (i, j, k) inside the bounding box (firstVoxel..lastVoxel on every axis).
  bool overlaps(int64_t i, int64_t j, int64_t k) const {
    const double x = double(i), y = double(j), z = double(k);
    return planeOverlaps(x, y, z) && projectionOverlaps(2, x, y) && projectionOverlaps(0, y, z) &&
           projectionOverlaps(1, z, x);
  }

 private:
  struct Edges {
    double nu[3], nv[3], d[3];
  };
  Vec3d n_, min_, max_;
  double offset_, d1_, d2_;
  Edges edges_[3];
};

}  // namespace voxlink::geometry
