// SPDX-License-Identifier: BSD-3-Clause
// The GL surface voxelizer against the exact CPU path: known voxel sets on synthetic triangles,
// and on the real meshes a subset of the exact voxels with close normals.
#include "render/gl/gl_voxelizer.h"

#include <gtest/gtest.h>

#include <set>

#include "geometry/mesh_loader.h"
#include "geometry/surface_voxelizer.h"
#include "geometry/voxel_set_compare.h"
#include "gl_test_context.h"
#include "tests/support/test_util.h"

namespace voxlink::render::gl {

namespace {

using geometry::SurfaceVoxel;
using geometry::TriangleMesh;
using geometry::VoxelGrid;

VoxelGrid unitGrid(uint32_t x, uint32_t y, uint32_t z) {
  VoxelGrid g;
  g.dims = {x, y, z};
  g.origin = {0.5, 0.5, 0.5};  // grid coordinate = world coordinate
  return g;
}

// Grid coordinates given directly (unitGrid).
TriangleMesh meshOf(const std::vector<std::array<float, 3>>& corners) {
  TriangleMesh m;
  for (const auto& c : corners) m.positions.insert(m.positions.end(), c.begin(), c.end());
  for (uint32_t i = 0; i < corners.size(); ++i) m.triangles.push_back(i);
  m.materials.resize(1);
  return m;
}

std::set<std::array<uint32_t, 3>> voxelSet(const std::vector<SurfaceVoxel>& voxels) {
  std::set<std::array<uint32_t, 3>> s;
  for (const SurfaceVoxel& v : voxels) s.insert({v.x, v.y, v.z});
  return s;
}

GlSurfaceVoxelization glVoxelize(const TriangleMesh& mesh, const VoxelGrid& grid,
                                 GlCoverage coverage = GlCoverage::kCenter) {
  auto voxelizer = GlSurfaceVoxelizer::create();
  EXPECT_TRUE(voxelizer) << voxelizer.message();
  if (!voxelizer) return {};
  GlVoxelizeOptions options;
  options.coverage = coverage;
  auto out = voxelizer->voxelize(mesh, grid, options);
  EXPECT_TRUE(out) << out.message();
  return out ? std::move(*out) : GlSurfaceVoxelization{};
}

TEST(GlVoxelizer, AxisAlignedQuadGivesTheKnownVoxels) {
  VOXLINK_REQUIRE_GL();
  // A quad at z = 3.25 over x 1.2..5.8, y 2.1..4.9: pixel centres x 1.5..5.5, y 2.5..4.5.
  const TriangleMesh mesh = meshOf({{1.2f, 2.1f, 3.25f},
                                    {5.8f, 2.1f, 3.25f},
                                    {5.8f, 4.9f, 3.25f},
                                    {1.2f, 2.1f, 3.25f},
                                    {5.8f, 4.9f, 3.25f},
                                    {1.2f, 4.9f, 3.25f}});
  const VoxelGrid grid = unitGrid(8, 8, 8);
  std::set<std::array<uint32_t, 3>> expected;
  for (uint32_t y = 2; y <= 4; ++y)
    for (uint32_t x = 1; x <= 5; ++x) expected.insert({x, y, 3});
  const GlSurfaceVoxelization gl = glVoxelize(mesh, grid);
  EXPECT_EQ(voxelSet(gl.surface.voxels), expected);
  EXPECT_EQ(gl.stats.fragments, 15u);
  for (const SurfaceVoxel& v : gl.surface.voxels) EXPECT_FLOAT_EQ(std::abs(v.normal[2]), 1.0f);
  auto exact = geometry::voxelizeSurface(mesh, grid);
  ASSERT_TRUE(exact);
  EXPECT_EQ(voxelSet(exact->voxels), expected);
  EXPECT_EQ(voxelSet(glVoxelize(mesh, grid, GlCoverage::kConservative).surface.voxels), expected);
}

TEST(GlVoxelizer, TiltedTriangleCrossesDepthVoxelsAtTheKnownColumns) {
  VOXLINK_REQUIRE_GL();
  // Plane z = 0.5 * x + 1 (dominant axis z), over x 0..8, y 0..8 as two triangles: column
  // (x, y) holds the voxel floor(0.5 * (x + 0.5) + 1).
  const TriangleMesh mesh =
      meshOf({{0, 0, 1}, {8, 0, 5}, {8, 8, 5}, {0, 0, 1}, {8, 8, 5}, {0, 8, 1}});
  const VoxelGrid grid = unitGrid(8, 8, 8);
  std::set<std::array<uint32_t, 3>> expected;
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 8; ++x) expected.insert({x, y, uint32_t(0.5 * (x + 0.5) + 1.0)});
  const GlSurfaceVoxelization gl = glVoxelize(mesh, grid);
  EXPECT_EQ(voxelSet(gl.surface.voxels), expected);
  auto exact = geometry::voxelizeSurface(mesh, grid);
  ASSERT_TRUE(exact);
  const auto cmp = geometry::compareSurfaceVoxels(exact->voxels, gl.surface.voxels);
  EXPECT_EQ(cmp.extra, 0u);
  EXPECT_GT(cmp.missing, 0u);  // the exact path also marks where the plane leaves a voxel
  EXPECT_LT(cmp.normalMaxDegrees, 0.05);  // float normals: acos near 1
  // Conservative: every voxel the plane crosses in each column, as the exact path.
  EXPECT_EQ(voxelSet(glVoxelize(mesh, grid, GlCoverage::kConservative).surface.voxels),
            voxelSet(exact->voxels));
}

TEST(GlVoxelizer, SliverBetweenPixelCentresIsMissedAndZeroAreaSkipped) {
  VOXLINK_REQUIRE_GL();
  // A sliver along y = 2.9..3.1 between centres 2.5 and 3.5, and a zero-area triangle.
  const TriangleMesh mesh = meshOf({{1.0f, 2.9f, 4.2f},
                                    {6.0f, 3.0f, 4.2f},
                                    {1.0f, 3.1f, 4.2f},
                                    {1.0f, 1.0f, 1.0f},
                                    {2.0f, 2.0f, 2.0f},
                                    {3.0f, 3.0f, 3.0f}});
  const VoxelGrid grid = unitGrid(8, 8, 8);
  const GlSurfaceVoxelization gl = glVoxelize(mesh, grid);
  EXPECT_TRUE(gl.surface.voxels.empty());
  EXPECT_EQ(gl.stats.zeroAreaTriangles, 1u);
  auto exact = geometry::voxelizeSurface(mesh, grid);
  ASSERT_TRUE(exact);
  EXPECT_GE(exact->voxels.size(), 2u * 5u);  // at least x 1..5, y 2 and 3, z 4
  // Conservative coverage finds the sliver's voxels.
  EXPECT_EQ(voxelSet(glVoxelize(mesh, grid, GlCoverage::kConservative).surface.voxels),
            voxelSet(exact->voxels));
}

TEST(GlVoxelizer, EmptyMeshAndClippedTriangle) {
  VOXLINK_REQUIRE_GL();
  const VoxelGrid grid = unitGrid(4, 4, 4);
  EXPECT_TRUE(glVoxelize(TriangleMesh{}, grid).surface.voxels.empty());
  // Reaches far outside the grid on every side: only voxels inside it.
  const TriangleMesh big = meshOf({{-20, -20, 2.5f}, {30, -20, 2.5f}, {-20, 30, 2.5f}});
  const GlSurfaceVoxelization gl = glVoxelize(big, grid);
  EXPECT_EQ(gl.surface.voxels.size(), 16u);
  for (const SurfaceVoxel& v : gl.surface.voxels) EXPECT_EQ(v.z, 2u);
}

TEST(GlVoxelizer, CornellWallsOnVoxelFacesAsTheExactPath) {
  VOXLINK_REQUIRE_DATA("mesh/mcguire_CornellBox-Original.obj");
  VOXLINK_REQUIRE_GL();
  auto mesh =
      geometry::loadMesh(::voxlink::testing::dataPath("mesh/mcguire_CornellBox-Original.obj"));
  ASSERT_TRUE(mesh) << mesh.message();
  VoxelGrid grid;  // the floor y = 0 on the face between layers 0 and 1 (exact in binary)
  grid.spacing = 1.0 / 64.0;
  grid.origin = {-1.25, -1.0 / 128.0, -1.25};
  grid.dims = {162, 132, 162};
  auto exact = geometry::voxelizeSurface(*mesh, grid);
  ASSERT_TRUE(exact);
  const GlSurfaceVoxelization conservative = glVoxelize(*mesh, grid, GlCoverage::kConservative);
  EXPECT_EQ(voxelSet(conservative.surface.voxels), voxelSet(exact->voxels));
  size_t floorVoxels = 0;
  for (const SurfaceVoxel& v : conservative.surface.voxels) {
    if (mesh->materials[v.material].name != "floor") continue;
    ++floorVoxels;
    EXPECT_EQ(v.y, 1u);
  }
  EXPECT_GT(floorVoxels, 100u * 100u);
  const auto centre = geometry::compareSurfaceVoxels(
      exact->voxels, glVoxelize(*mesh, grid, GlCoverage::kCenter).surface.voxels);
  EXPECT_EQ(centre.extra, 0u);
}

TEST(GlVoxelizer, BatchesGiveTheSameVoxels) {
  VOXLINK_REQUIRE_DATA("mesh/vtk_bunny.ply");
  VOXLINK_REQUIRE_GL();
  auto mesh = geometry::loadMesh(::voxlink::testing::dataPath("mesh/vtk_bunny.ply"));
  ASSERT_TRUE(mesh) << mesh.message();
  auto grid = geometry::fitGrid(geometry::meshBounds(*mesh), 64);
  ASSERT_TRUE(grid);
  auto voxelizer = GlSurfaceVoxelizer::create();
  ASSERT_TRUE(voxelizer) << voxelizer.message();
  auto whole = voxelizer->voxelize(*mesh, *grid);
  ASSERT_TRUE(whole) << whole.message();
  GlVoxelizeOptions small;
  small.batchFragments = 5000;
  auto batched = voxelizer->voxelize(*mesh, *grid, small);
  ASSERT_TRUE(batched) << batched.message();
  EXPECT_EQ(whole->stats.draws, 1);
  EXPECT_GT(batched->stats.draws, 10);
  EXPECT_EQ(voxelSet(batched->surface.voxels), voxelSet(whole->surface.voxels));
  const auto cmp = geometry::compareSurfaceVoxels(whole->surface.voxels, batched->surface.voxels);
  EXPECT_EQ(cmp.materialMismatches, 0u);
  EXPECT_LT(cmp.normalMaxDegrees, 0.05);
}

class GlVoxelizerRealMesh : public ::testing::TestWithParam<std::tuple<const char*, uint32_t>> {};

TEST_P(GlVoxelizerRealMesh, SubsetOfTheExactVoxels) {
  const auto [file, resolution] = GetParam();
  VOXLINK_REQUIRE_DATA(file);
  VOXLINK_REQUIRE_GL();
  auto mesh = geometry::loadMesh(::voxlink::testing::dataPath(file));
  ASSERT_TRUE(mesh) << mesh.message();
  auto grid = geometry::fitGrid(geometry::meshBounds(*mesh), resolution);
  ASSERT_TRUE(grid);
  auto exact = geometry::voxelizeSurface(*mesh, *grid);
  ASSERT_TRUE(exact);
  const GlSurfaceVoxelization gl = glVoxelize(*mesh, *grid);
  const auto cmp = geometry::compareSurfaceVoxels(exact->voxels, gl.surface.voxels);
  std::printf("%s at %u: exact %llu, gl %llu, missing %llu, extra %llu, normal %.2f/%.2f deg\n",
              file, resolution, (unsigned long long)cmp.reference,
              (unsigned long long)cmp.candidate, (unsigned long long)cmp.missing,
              (unsigned long long)cmp.extra, cmp.normalMeanDegrees, cmp.normalMaxDegrees);
  EXPECT_EQ(cmp.extra, 0u);
  EXPECT_GT(cmp.common, cmp.reference / 2);
  EXPECT_EQ(gl.stats.zeroAreaTriangles, exact->zeroAreaTriangles);
}

TEST_P(GlVoxelizerRealMesh, ConservativeMatchesTheExactVoxels) {
  const auto [file, resolution] = GetParam();
  VOXLINK_REQUIRE_DATA(file);
  VOXLINK_REQUIRE_GL();
  auto mesh = geometry::loadMesh(::voxlink::testing::dataPath(file));
  ASSERT_TRUE(mesh) << mesh.message();
  auto grid = geometry::fitGrid(geometry::meshBounds(*mesh), resolution);
  ASSERT_TRUE(grid);
  auto exact = geometry::voxelizeSurface(*mesh, *grid);
  ASSERT_TRUE(exact);
  const GlSurfaceVoxelization gl = glVoxelize(*mesh, *grid, GlCoverage::kConservative);
  const auto cmp = geometry::compareSurfaceVoxels(exact->voxels, gl.surface.voxels);
  std::printf(
      "%s at %u conservative: exact %llu, gl %llu, missing %llu, extra %llu, normal "
      "%.2f/%.2f deg\n",
      file, resolution, (unsigned long long)cmp.reference, (unsigned long long)cmp.candidate,
      (unsigned long long)cmp.missing, (unsigned long long)cmp.extra, cmp.normalMeanDegrees,
      cmp.normalMaxDegrees);
  EXPECT_LE(cmp.missing + cmp.extra, cmp.reference / 1000);
}

INSTANTIATE_TEST_SUITE_P(
    Meshes, GlVoxelizerRealMesh,
    ::testing::Combine(::testing::Values("mesh/vtk_bunny.ply", "mesh/vtk_horse.ply",
                                         "mesh/stanford_dragon_decimated.ply",
                                         "mesh/mcguire_CornellBox-Original.obj"),
                       ::testing::Values(64u, 128u)));

}  // namespace
}  // namespace voxlink::render::gl
