// SPDX-License-Identifier: BSD-3-Clause
// voxelizeSurface against the brute force (every voxel x every triangle, plain SAT), the hard
// cases, and real meshes.
#include "geometry/surface_voxelizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <unordered_map>
#include <unordered_set>

#include "base/parallel_for.h"
#include "geometry/mesh_loader.h"
#include "tests/geometry/voxel_test_util.h"
#include "tests/support/test_util.h"

namespace voxlink::geometry {
namespace {

void addTriangle(TriangleMesh& mesh, std::array<float, 3> a, std::array<float, 3> b,
                 std::array<float, 3> c, uint16_t material = 0) {
  const auto base = uint32_t(mesh.vertexCount());
  for (const auto& p : {a, b, c}) mesh.positions.insert(mesh.positions.end(), p.begin(), p.end());
  mesh.triangles.insert(mesh.triangles.end(), {base, base + 1, base + 2});
  mesh.triangleMaterials.push_back(material);
}

SurfaceVoxelization voxelize(const TriangleMesh& mesh, const VoxelGrid& grid,
                             SurfaceVoxelizeOptions options = {}) {
  auto result = voxelizeSurface(mesh, grid, options);
  EXPECT_TRUE(result) << result.message();
  return result ? std::move(result).value() : SurfaceVoxelization{};
}

// Voxels, order, normals and materials against the brute force.
void expectMatchesBruteForce(const TriangleMesh& mesh, const VoxelGrid& grid) {
  const auto expected = testing::bruteForceSurface(mesh, grid);
  const SurfaceVoxelization got = voxelize(mesh, grid);
  ASSERT_EQ(got.voxels.size(), expected.size());
  size_t n = 0;
  for (const auto& [key, triangles] : expected) {  // std::map: ascending key = (z, y, x)
    const SurfaceVoxel& v = got.voxels[n++];
    ASSERT_EQ(voxelKey(v.x, v.y, v.z), key);
    // Dominant triangle by area, area-weighted normal.
    double best = -1.0, sum[3] = {0, 0, 0};
    uint32_t dominant = 0;
    for (uint32_t t : triangles) {
      const Vec3d a = testing::cornerInGrid(mesh, grid, t, 0),
                  b = testing::cornerInGrid(mesh, grid, t, 1),
                  c = testing::cornerInGrid(mesh, grid, t, 2);
      const Vec3d e{b[0] - a[0], b[1] - a[1], b[2] - a[2]},
          f{c[0] - b[0], c[1] - b[1], c[2] - b[2]};
      const Vec3d cr{e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2],
                     e[0] * f[1] - e[1] * f[0]};
      const double len = std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
      if (float(0.5 * len) > best) {
        best = float(0.5 * len);
        dominant = t;
      }
      for (int i = 0; i < 3; ++i) sum[i] += 0.5 * cr[i];
    }
    EXPECT_EQ(v.material, mesh.triangleMaterials[dominant]);
    const double len = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    if (len > 1e-3) {
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(v.normal[i], sum[i] / len, 1e-4);
    }
  }
}

VoxelGrid smallGrid() {
  VoxelGrid grid;
  grid.origin = {-0.3, 0.1, -0.7};
  grid.spacing = 0.37;
  grid.dims = {13, 11, 9};
  return grid;
}

TEST(SurfaceVoxelizer, RandomTrianglesMatchBruteForce) {
  std::mt19937 rng(11);
  const VoxelGrid grid = smallGrid();
  // Some triangles reach outside the grid on every side.
  std::uniform_real_distribution<float> x(-1.0f, 5.0f), y(-0.5f, 4.6f), z(-1.5f, 3.5f);
  std::uniform_real_distribution<float> jitter(-0.3f, 0.3f);
  for (int round = 0; round < 6; ++round) {
    TriangleMesh mesh;
    for (int t = 0; t < 40; ++t) {
      const std::array<float, 3> a{x(rng), y(rng), z(rng)};
      auto near = [&] {
        return std::array<float, 3>{a[0] + jitter(rng), a[1] + jitter(rng), a[2] + jitter(rng)};
      };
      if (t % 3 == 0)  // small triangles
        addTriangle(mesh, a, near(), near(), uint16_t(t % 5));
      else
        addTriangle(mesh, a, {x(rng), y(rng), z(rng)}, {x(rng), y(rng), z(rng)}, uint16_t(t % 5));
    }
    expectMatchesBruteForce(mesh, grid);
  }
}

TEST(SurfaceVoxelizer, SmallMeshesMatchBruteForce) {
  // A closed tetrahedron and an octahedron, including vertices on voxel faces and corners.
  VoxelGrid grid;
  grid.origin = {0.0, 0.0, 0.0};
  grid.spacing = 0.25;
  grid.dims = {16, 16, 16};
  TriangleMesh tetra;
  const std::array<float, 3> p0{0.375f, 0.375f, 0.375f}, p1{3.125f, 0.5f, 0.625f},
      p2{0.5f, 3.0f, 1.0f}, p3{1.0f, 1.0f, 3.3f};
  addTriangle(tetra, p0, p2, p1, 0);
  addTriangle(tetra, p0, p1, p3, 1);
  addTriangle(tetra, p1, p2, p3, 2);
  addTriangle(tetra, p2, p0, p3, 3);
  expectMatchesBruteForce(tetra, grid);
  TriangleMesh octa;
  const float c = 2.0f, r = 1.5f;
  const std::array<float, 3> px{c + r, c, c}, nx{c - r, c, c}, py{c, c + r, c}, ny{c, c - r, c},
      pz{c, c, c + r}, nz{c, c, c - r};
  for (const auto& [a, b] : {std::pair{px, py}, {py, nx}, {nx, ny}, {ny, px}}) {
    addTriangle(octa, a, b, pz, 0);
    addTriangle(octa, b, a, nz, 1);
  }
  expectMatchesBruteForce(octa, grid);
}

TEST(SurfaceVoxelizer, QuadOnAVoxelPlaneIsOneVoxelThick) {
  VoxelGrid grid;  // voxel i covers [i - 0.5, i + 0.5]
  grid.dims = {8, 8, 8};
  TriangleMesh mesh;  // the plane z = 2.5: the face between layers 2 and 3
  addTriangle(mesh, {0.7f, 0.7f, 2.5f}, {3.3f, 0.7f, 2.5f}, {3.3f, 3.3f, 2.5f});
  addTriangle(mesh, {0.7f, 0.7f, 2.5f}, {3.3f, 3.3f, 2.5f}, {0.7f, 3.3f, 2.5f});
  const SurfaceVoxelization result = voxelize(mesh, grid);
  // x and y from 0.7 to 3.3 cover voxels 1..3; z = 2.5 is layer 3 only.
  ASSERT_EQ(result.voxels.size(), 9u);
  for (const SurfaceVoxel& v : result.voxels) {
    EXPECT_EQ(v.z, 3u);
    EXPECT_GE(v.x, 1u);
    EXPECT_LE(v.x, 3u);
    EXPECT_FLOAT_EQ(v.normal[2], 1.0f);
  }
  EXPECT_EQ(result.normalError.maxDegrees, 0.0);
  expectMatchesBruteForce(mesh, grid);
}

TEST(SurfaceVoxelizer, CornellFloorOnAVoxelFaceIsOneLayer) {
  VOXLINK_REQUIRE_DATA("mesh/mcguire_CornellBox-Original.obj");
  auto mesh = loadMesh(::voxlink::testing::dataPath("mesh/mcguire_CornellBox-Original.obj"));
  ASSERT_TRUE(mesh) << mesh.message();
  VoxelGrid grid;  // the floor y = 0 lies on the face between layers 0 and 1 (exact in binary)
  grid.spacing = 1.0 / 64.0;
  grid.origin = {-1.25, -1.0 / 128.0, -1.25};
  grid.dims = {162, 132, 162};
  ASSERT_EQ(grid.toGrid(0.0, 0.0, 0.0)[1], 1.0);
  const SurfaceVoxelization result = voxelize(*mesh, grid);
  size_t floorVoxels = 0;
  for (const SurfaceVoxel& v : result.voxels) {
    if (mesh->materials[v.material].name != "floor") continue;
    ++floorVoxels;
    EXPECT_EQ(v.y, 1u);
  }
  EXPECT_GT(floorVoxels, 100u * 100u);
  size_t lightVoxels = 0;
  for (const SurfaceVoxel& v : result.voxels)
    lightVoxels += mesh->materials[v.material].name == "light";
  EXPECT_GT(lightVoxels, 0u);
}

TEST(SurfaceVoxelizer, TinyTrianglesMarkTheVoxelTheyLieIn) {
  VoxelGrid grid;
  grid.dims = {4, 4, 4};
  TriangleMesh mesh;
  addTriangle(mesh, {1.1f, 2.1f, 0.9f}, {1.101f, 2.1f, 0.9f}, {1.1f, 2.101f, 0.901f});
  const SurfaceVoxelization result = voxelize(mesh, grid);
  ASSERT_EQ(result.voxels.size(), 1u);
  EXPECT_EQ(result.voxels[0].x, 1u);
  EXPECT_EQ(result.voxels[0].y, 2u);
  EXPECT_EQ(result.voxels[0].z, 1u);
}

TEST(SurfaceVoxelizer, ZeroAreaTrianglesAreSkippedAndCounted) {
  VoxelGrid grid;
  grid.dims = {6, 6, 6};
  TriangleMesh mesh;
  addTriangle(mesh, {0.2f, 0.3f, 1.0f}, {4.0f, 3.0f, 2.0f}, {1.0f, 4.2f, 3.5f});
  const SurfaceVoxelization before = voxelize(mesh, grid);
  addTriangle(mesh, {1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f});  // a point
  addTriangle(mesh, {0.0f, 0.0f, 0.0f}, {2.0f, 2.0f, 2.0f}, {4.0f, 4.0f, 4.0f});  // a segment
  addTriangle(mesh, {0.0f, 1.0f, 0.0f}, {3.0f, 1.0f, 0.0f}, {3.0f, 1.0f, 0.0f});  // two equal
  const SurfaceVoxelization after = voxelize(mesh, grid);
  EXPECT_EQ(after.zeroAreaTriangles, 3u);
  ASSERT_EQ(after.voxels.size(), before.voxels.size());
  for (size_t i = 0; i < after.voxels.size(); ++i) {
    EXPECT_EQ(voxelKey(after.voxels[i].x, after.voxels[i].y, after.voxels[i].z),
              voxelKey(before.voxels[i].x, before.voxels[i].y, before.voxels[i].z));
  }
}

TEST(SurfaceVoxelizer, MeshTouchingTheGridFacesAndPartlyOutside) {
  // A box surface fitted to the grid: its faces lie on the first and last voxel centres.
  TriangleMesh cube;
  const float s = 1.0f;
  const std::array<float, 3> v[8] = {{0, 0, 0}, {s, 0, 0}, {s, s, 0}, {0, s, 0},
                                     {0, 0, s}, {s, 0, s}, {s, s, s}, {0, s, s}};
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
  for (const auto& f : faces) {
    addTriangle(cube, v[f[0]], v[f[1]], v[f[2]]);
    addTriangle(cube, v[f[0]], v[f[2]], v[f[3]]);
  }
  auto grid = fitGrid(meshBounds(cube), 10);
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->dims[0], 10u);
  EXPECT_EQ(grid->dims[2], 10u);
  const SurfaceVoxelization result = voxelize(cube, *grid);
  EXPECT_EQ(result.voxels.size(), 10u * 10u * 10u - 8u * 8u * 8u);  // the shell, one voxel thick
  expectMatchesBruteForce(cube, *grid);
  // The same cube in a grid that cuts it: only voxels inside the grid, as the brute force.
  VoxelGrid cut = *grid;
  cut.origin = {0.35, -0.2, 0.5};
  cut.dims = {6, 4, 9};
  expectMatchesBruteForce(cube, cut);
  // Wholly outside: nothing.
  cut.origin = {5.0, 5.0, 5.0};
  EXPECT_TRUE(voxelize(cube, cut).voxels.empty());
}

TEST(SurfaceVoxelizer, EmptyMeshAndBadInput) {
  VoxelGrid grid;
  grid.dims = {4, 4, 4};
  EXPECT_TRUE(voxelize(TriangleMesh{}, grid).voxels.empty());
  TriangleMesh bad;
  bad.positions = {0, 0, 0};
  bad.triangles = {0, 0, 1};
  auto result = voxelizeSurface(bad, grid);
  ASSERT_FALSE(result);
  EXPECT_NE(result.message().find("vertex index 1"), std::string::npos) << result.message();
  grid.dims = {4, 0, 4};
  EXPECT_FALSE(voxelizeSurface(TriangleMesh{}, grid));
  grid.dims = {4, 4, kMaxGridDim + 1};
  EXPECT_FALSE(voxelizeSurface(TriangleMesh{}, grid));
}

TEST(SurfaceVoxelizer, OverlapLimitIsAnError) {
  VoxelGrid grid;
  grid.dims = {32, 32, 32};
  TriangleMesh mesh;
  addTriangle(mesh, {0, 0, 0}, {31, 0, 0}, {0, 31, 31});
  SurfaceVoxelizeOptions options;
  options.maxOverlaps = 100;
  auto result = voxelizeSurface(mesh, grid, options);
  ASSERT_FALSE(result);
  EXPECT_EQ(result.code(), ErrorCode::kTooLarge);
}

// Real meshes: the same voxels with 1 or 2 threads; the OBJ and the PLY bunny (the same surface,
// parsed by different assimp readers whose float parsing can differ in the last bit) agree to a
// few voxels.
TEST(SurfaceVoxelizer, BunnyIsStableAcrossThreadCountsAndFileFormats) {
  VOXLINK_REQUIRE_DATA("mesh/c3dtm_stanford-bunny.obj");
  VOXLINK_REQUIRE_DATA("mesh/vtk_bunny.ply");
  auto obj = loadMesh(::voxlink::testing::dataPath("mesh/c3dtm_stanford-bunny.obj"));
  auto ply = loadMesh(::voxlink::testing::dataPath("mesh/vtk_bunny.ply"));
  ASSERT_TRUE(obj && ply);
  auto grid = fitGrid(meshBounds(*ply), 192);
  ASSERT_TRUE(grid);
  const SurfaceVoxelization a = voxelize(*ply, *grid);
  SurfaceVoxelization b;
  {
    base::ThreadLimit one(1);
    b = voxelize(*ply, *grid);
  }
  ASSERT_EQ(a.voxels.size(), b.voxels.size());
  for (size_t i = 0; i < a.voxels.size(); ++i) {
    ASSERT_EQ(voxelKey(a.voxels[i].x, a.voxels[i].y, a.voxels[i].z),
              voxelKey(b.voxels[i].x, b.voxels[i].y, b.voxels[i].z));
    ASSERT_EQ(a.voxels[i].normal, b.voxels[i].normal);
    ASSERT_EQ(a.voxels[i].material, b.voxels[i].material);
  }
  // The normal error goes into a scene file's META: the same bits on any number of threads.
  EXPECT_EQ(a.normalError.meanDegrees, b.normalError.meanDegrees);
  EXPECT_EQ(a.normalError.p95Degrees, b.normalError.p95Degrees);
  EXPECT_EQ(a.normalError.maxDegrees, b.normalError.maxDegrees);
  const SurfaceVoxelization fromObj = voxelize(*obj, *grid);
  const double relative =
      std::abs(double(fromObj.voxels.size()) - double(a.voxels.size())) / double(a.voxels.size());
  EXPECT_LT(relative, 1e-4) << fromObj.voxels.size() << " vs " << a.voxels.size();
  EXPECT_GT(a.voxels.size(), 50000u);
  EXPECT_GT(a.normalError.pairs, a.voxels.size());
  EXPECT_LE(a.normalError.meanDegrees, a.normalError.p95Degrees);
  EXPECT_LE(a.normalError.p95Degrees, a.normalError.maxDegrees);
}

double pointTriangleDistance(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  // Closest point by barycentric region (Ericson, Real-Time Collision Detection 5.1.5).
  auto sub = [](const Vec3d& u, const Vec3d& v) {
    return Vec3d{u[0] - v[0], u[1] - v[1], u[2] - v[2]};
  };
  auto dot = [](const Vec3d& u, const Vec3d& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  auto at = [&](double v, double w) {
    return Vec3d{a[0] + v * (b[0] - a[0]) + w * (c[0] - a[0]),
                 a[1] + v * (b[1] - a[1]) + w * (c[1] - a[1]),
                 a[2] + v * (b[2] - a[2]) + w * (c[2] - a[2])};
  };
  const Vec3d ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  Vec3d q;
  if (d1 <= 0 && d2 <= 0) {
    q = a;
  } else {
    const Vec3d bp = sub(p, b);
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    const Vec3d cp = sub(p, c);
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d3 >= 0 && d4 <= d3)
      q = b;
    else if (d6 >= 0 && d5 <= d6)
      q = c;
    else if (vc <= 0 && d1 >= 0 && d3 <= 0)
      q = at(d1 / (d1 - d3), 0);
    else if (vb <= 0 && d2 >= 0 && d6 <= 0)
      q = at(0, d2 / (d2 - d6));
    else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
      const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      q = {b[0] + w * (c[0] - b[0]), b[1] + w * (c[1] - b[1]), b[2] + w * (c[2] - b[2])};
    } else {
      const double denom = 1.0 / (va + vb + vc);
      q = at(vb * denom, vc * denom);
    }
  }
  const Vec3d d = sub(p, q);
  return std::sqrt(dot(d, d));
}

TEST(SurfaceVoxelizer, EveryVoxelOfARealMeshIsNearTheSurface) {
  VOXLINK_REQUIRE_DATA("mesh/stanford_dragon_decimated.ply");
  auto mesh = loadMesh(::voxlink::testing::dataPath("mesh/stanford_dragon_decimated.ply"));
  ASSERT_TRUE(mesh);
  auto grid = fitGrid(meshBounds(*mesh), 160);
  ASSERT_TRUE(grid);
  const SurfaceVoxelization result = voxelize(*mesh, *grid);
  std::unordered_map<uint64_t, double> nearest;
  for (const SurfaceVoxel& v : result.voxels) nearest[voxelKey(v.x, v.y, v.z)] = 1e30;
  // Distances in grid units from each voxel centre (i + 0.5, ...) to the triangles whose
  // bounding box, grown by the half diagonal, holds it.
  const double halfDiagonal = std::sqrt(3.0) / 2.0;
  for (size_t t = 0; t < mesh->triangleCount(); ++t) {
    const Vec3d a = testing::cornerInGrid(*mesh, *grid, t, 0),
                b = testing::cornerInGrid(*mesh, *grid, t, 1),
                c = testing::cornerInGrid(*mesh, *grid, t, 2);
    int64_t lo[3], hi[3];
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::max<int64_t>(0, int64_t(std::floor(std::min({a[i], b[i], c[i]}) - 1.0)));
      hi[i] = std::min<int64_t>(grid->dims[i] - 1,
                                int64_t(std::floor(std::max({a[i], b[i], c[i]}) + 1.0)));
    }
    for (int64_t z = lo[2]; z <= hi[2]; ++z)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t x = lo[0]; x <= hi[0]; ++x) {
          auto it = nearest.find(voxelKey(uint32_t(x), uint32_t(y), uint32_t(z)));
          if (it == nearest.end()) continue;
          it->second =
              std::min(it->second, pointTriangleDistance({x + 0.5, y + 0.5, z + 0.5}, a, b, c));
        }
  }
  for (const auto& [key, distance] : nearest) ASSERT_LE(distance, halfDiagonal + 1e-9) << key;
  EXPECT_EQ(nearest.size(), result.voxels.size());
}

}  // namespace
}  // namespace voxlink::geometry
