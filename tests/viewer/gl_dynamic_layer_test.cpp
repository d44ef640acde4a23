// SPDX-License-Identifier: BSD-3-Clause
// The dynamic layer (GPU-side re-voxelization) against the GL voxelizer's host path on a real
// mesh: the same voxels, normals within a fixed-point rounding, a moved mesh gives the moved
// voxels (the previous frame cleared), and a pool too small is an error, not a silent gap.
#include "render/gl/gl_dynamic_layer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "geometry/mesh_loader.h"
#include "geometry/voxel_grid.h"
#include "gl_test_context.h"
#include "render/gl/gl_voxelizer.h"
#include "tests/support/test_util.h"

namespace voxlink::render::gl {
namespace {

struct Fixture {
  geometry::TriangleMesh mesh;
  geometry::VoxelGrid grid;
  std::vector<float> gridPositions;
};

Fixture bunnyAt(uint32_t resolution) {
  Fixture f;
  auto mesh = geometry::loadMesh(::voxlink::testing::dataPath("mesh/vtk_bunny.ply"));
  EXPECT_TRUE(mesh) << mesh.message();
  f.mesh = std::move(*mesh);
  geometry::Bounds3 b;
  for (size_t v = 0; v < f.mesh.vertexCount(); ++v)
    b.add(f.mesh.positions[3 * v], f.mesh.positions[3 * v + 1], f.mesh.positions[3 * v + 2]);
  f.grid = *geometry::fitGrid(b, resolution);
  for (size_t v = 0; v < f.mesh.vertexCount(); ++v) {
    const auto g = f.grid.toGrid(f.mesh.positions[3 * v], f.mesh.positions[3 * v + 1],
                                 f.mesh.positions[3 * v + 2]);
    f.gridPositions.insert(f.gridPositions.end(), {float(g[0]), float(g[1]), float(g[2])});
  }
  return f;
}

std::vector<uint32_t> materials(const Fixture& f, uint32_t m) {
  return std::vector<uint32_t>(f.mesh.triangleCount(), m);
}

Result<GlDynamicLayer> layerFor(const Fixture& f, uint64_t bricks = 0) {
  std::array<double, 3> extent{};
  for (int a = 0; a < 3; ++a) extent[a] = f.grid.dims[a];
  return GlDynamicLayer::create(f.grid.dims, 8,
                                bricks ? bricks : dynamicBrickBound(extent, 8, f.grid.dims));
}

TEST(GlDynamicLayer, SameVoxelsAndNormalsAsTheHostPath) {
  VOXLINK_REQUIRE_GL();
  Fixture f = bunnyAt(96);
  auto voxelizer = GlSurfaceVoxelizer::create();
  ASSERT_TRUE(voxelizer) << voxelizer.message();
  auto host = voxelizer->voxelize(f.mesh, f.grid);  // conservative, area-weighted normals
  ASSERT_TRUE(host) << host.message();
  auto layer = layerFor(f);
  ASSERT_TRUE(layer) << layer.message();
  ASSERT_TRUE(layer->update(f.gridPositions, f.mesh.triangles, materials(f, 7)).isOk());
  ASSERT_TRUE(layer->checkLastUpdate().isOk());
  const auto gpu = layer->readVoxels();
  ASSERT_EQ(gpu.size(), host->surface.voxels.size());
  std::map<uint64_t, std::array<float, 3>> hostNormals;
  for (const auto& v : host->surface.voxels)
    hostNormals[geometry::voxelKey(v.x, v.y, v.z)] = v.normal;
  size_t compared = 0, off = 0;
  for (const auto& [key, e] : gpu) {
    ASSERT_TRUE(hostNormals.count(key)) << "voxel not in the host's set";
    EXPECT_EQ(e[3], 8);  // material + 1
    const double len = std::sqrt(double(e[0]) * e[0] + double(e[1]) * e[1] + double(e[2]) * e[2]);
    if (len < 64) continue;  // sides that cancel: no meaningful direction on either path
    const auto& h = hostNormals[key];
    const double cosine = (e[0] * h[0] + e[1] * h[1] + e[2] * h[2]) / len;
    ++compared;
    off += cosine < std::cos(1.0 * M_PI / 180);  // more than 1 degree apart
  }
  EXPECT_GT(compared, gpu.size() * 99 / 100);
  EXPECT_LE(off, compared / 1000) << off << " of " << compared << " normals > 1 degree off";
}

TEST(GlDynamicLayer, AMovedMeshGivesTheMovedVoxels) {
  VOXLINK_REQUIRE_GL();
  Fixture f = bunnyAt(64);
  auto layer = layerFor(f);
  ASSERT_TRUE(layer) << layer.message();
  // Shrunk about the origin so that a move by whole voxels stays inside the grid.
  for (float& p : f.gridPositions) p *= 0.5f;
  ASSERT_TRUE(layer->update(f.gridPositions, f.mesh.triangles, materials(f, 0)).isOk());
  const auto before = layer->readVoxels();
  ASSERT_GT(before.size(), 100u);
  std::vector<float> moved = f.gridPositions;
  for (size_t v = 0; v < moved.size(); v += 3) {
    moved[v] += 9;
    moved[v + 1] += 5;
    moved[v + 2] += 3;
  }
  ASSERT_TRUE(layer->update(moved, f.mesh.triangles, materials(f, 0)).isOk());
  ASSERT_TRUE(layer->checkLastUpdate().isOk());
  const auto after = layer->readVoxels();
  ASSERT_EQ(after.size(), before.size());
  for (size_t i = 0; i < before.size(); ++i) {
    const auto a = geometry::voxelFromKey(before[i].first);
    ASSERT_EQ(after[i].first, geometry::voxelKey(a[0] + 9, a[1] + 5, a[2] + 3)) << i;
    // The same sums up to the rounding of the moved float vertices (units of 1/4096).
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(after[i].second[c], before[i].second[c], 4) << i;
    EXPECT_EQ(after[i].second[3], before[i].second[3]);
  }
}

TEST(GlDynamicLayer, APoolTooSmallIsAnError) {
  VOXLINK_REQUIRE_GL();
  Fixture f = bunnyAt(64);
  auto layer = layerFor(f, 2);
  ASSERT_TRUE(layer) << layer.message();
  ASSERT_TRUE(layer->update(f.gridPositions, f.mesh.triangles, materials(f, 0)).isOk());
  const Status s = layer->checkLastUpdate();
  EXPECT_FALSE(s.isOk());
  EXPECT_NE(s.message().find("bricks exceed its 2"), std::string::npos) << s.message();
}

// Each update zeroes only the pool slots the last one used (and frees their hash keys): a turned
// and moved mesh after another frame gives exactly the layer a fresh one does.
TEST(GlDynamicLayer, AnUpdateAfterAnotherGivesTheSameLayerAsAFreshOne) {
  VOXLINK_REQUIRE_GL();
  Fixture f = bunnyAt(96);
  std::vector<float> moved = f.gridPositions;
  for (size_t v = 0; v < moved.size(); v += 3) {
    const float x = moved[v] - 48, z = moved[v + 2] - 48;
    moved[v] = 48 + 0.8f * x - 0.6f * z + 3.3f;
    moved[v + 2] = 48 + 0.6f * x + 0.8f * z;
  }
  auto a = layerFor(f);
  ASSERT_TRUE(a);
  ASSERT_TRUE(a->update(moved, f.mesh.triangles, materials(f, 0)).isOk());
  const auto fresh = a->readVoxels();
  auto b = layerFor(f);
  ASSERT_TRUE(b);
  ASSERT_TRUE(b->update(f.gridPositions, f.mesh.triangles, materials(f, 0)).isOk());
  ASSERT_TRUE(b->update(moved, f.mesh.triangles, materials(f, 0)).isOk());
  const auto again = b->readVoxels();
  ASSERT_EQ(fresh.size(), again.size());
  size_t diff = 0;
  for (size_t i = 0; i < fresh.size(); ++i) diff += fresh[i] != again[i];
  EXPECT_EQ(diff, 0u);
}
// A pool split over four storage buffers (a test cap on bytes per buffer) gives the layer one
// buffer gives, for a fresh update and for one on a kept layer; a split pool still too small is
// the error, naming the per-buffer limit.
TEST(GlDynamicLayer, APoolSplitOverBuffersGivesTheSameLayer) {
  VOXLINK_REQUIRE_GL();
  Fixture f = bunnyAt(96);
  std::vector<float> moved = f.gridPositions;
  for (size_t v = 0; v < moved.size(); v += 3) moved[v] += 17.5f;
  std::array<double, 3> extent{};
  for (int a = 0; a < 3; ++a) extent[a] = f.grid.dims[a];
  const uint64_t bound = dynamicBrickBound(extent, 8, f.grid.dims), brickBytes = 8 * 8 * 8 * 16;
  auto one = GlDynamicLayer::create(f.grid.dims, 8, bound);
  ASSERT_TRUE(one) << one.message();
  ASSERT_EQ(one->poolBuffers(), 1u);
  ASSERT_TRUE(one->update(f.gridPositions, f.mesh.triangles, materials(f, 2)).isOk());
  ASSERT_TRUE(one->keep().isOk());
  const auto voxels = one->readVoxels();
  std::set<std::array<uint32_t, 3>> bricks;
  for (const auto& v : voxels) {
    const auto c = geometry::voxelFromKey(v.first);
    bricks.insert({c[0] / 8, c[1] / 8, c[2] / 8});
  }
  ASSERT_GT(bricks.size(), 8u);
  // Buffers of 3/4 of the bricks used: the kept bricks too take two buffers.
  auto four = GlDynamicLayer::create(f.grid.dims, 8, bound, bricks.size() * 3 / 4 * brickBytes);
  ASSERT_TRUE(four) << four.message();
  ASSERT_EQ(four->poolBuffers(), 4u);
  ASSERT_TRUE(four->update(f.gridPositions, f.mesh.triangles, materials(f, 2)).isOk());
  ASSERT_TRUE(four->keep().isOk());
  EXPECT_EQ(voxels, four->readVoxels());
  for (GlDynamicLayer* layer : {&*one, &*four}) {
    ASSERT_TRUE(layer->update(moved, f.mesh.triangles, materials(f, 5), true).isOk());
    ASSERT_TRUE(layer->checkLastUpdate().isOk());
  }
  const auto both = one->readVoxels();
  EXPECT_GT(both.size(), voxels.size());
  EXPECT_EQ(both, four->readVoxels());
  auto small = GlDynamicLayer::create(f.grid.dims, 8, bound, 8 * brickBytes);  // 4 x 8 bricks
  ASSERT_TRUE(small) << small.message();
  ASSERT_TRUE(small->update(f.gridPositions, f.mesh.triangles, materials(f, 2)).isOk());
  const Status s = small->checkLastUpdate();
  ASSERT_FALSE(s.isOk());
  EXPECT_NE(s.message().find("bricks exceed its 32 (4 of at most 4 storage buffers of 8 bricks"),
            std::string::npos)
      << s.message();
  EXPECT_NE(s.message().find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"), std::string::npos);
}

}  // namespace
}  // namespace voxlink::render::gl
