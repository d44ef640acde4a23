// SPDX-License-Identifier: BSD-3-Clause
// PLY triangle strips (`element tristrips`): assimp 5.2 kept one triangle of them (a
// 268,686-triangle head became a scene "from 1 triangles"). A strip mesh must voxelize to the
// voxels of the same surface stored as triangles; a mesh that lost faces is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <set>
#include <sstream>
#include <tuple>

#include "geometry/mesh_loader.h"
#include "geometry/surface_voxelizer.h"
#include "geometry/voxel_grid.h"
#include "tests/support/test_util.h"

namespace voxlink::geometry {
namespace {

using testing::TempDir;

constexpr int kSide = 13;  // vertices per side of the height field

// Multiples of 1/8: the ASCII and binary files hold the same floats.
float heightAt(int i, int j) {
  return std::round(16.0f * std::sin(0.7f * i) * std::cos(0.5f * j)) / 8;
}
int vertex(int i, int j) { return j * kSide + i; }

std::string vertexHeader(const char* format, int faceLikeCount, const char* element,
                         const char* countType) {
  std::ostringstream h;
  h << "ply\nformat " << format << " 1.0\ncomment a height field\nelement vertex " << kSide * kSide
    << "\nproperty float x\nproperty float y\nproperty float z\nelement " << element << " "
    << faceLikeCount << "\nproperty list " << countType << " int vertex_indices\nend_header\n";
  return h.str();
}

// Row j's strip: v(0,j+1) v(0,j) v(1,j+1) v(1,j) ...: triangles (v(i,j+1) v(i,j) v(i+1,j+1))
// and, wound the other way, (v(i+1,j+1) v(i,j) v(i+1,j)).
std::vector<int> stripIndices() {
  std::vector<int> all;
  for (int j = 0; j + 1 < kSide; ++j) {
    if (j > 0) all.push_back(-1);
    for (int i = 0; i < kSide; ++i) {
      all.push_back(vertex(i, j + 1));
      all.push_back(vertex(i, j));
    }
  }
  return all;
}

// The same triangles as faces.
std::vector<std::array<int, 3>> faceTriangles() {
  std::vector<std::array<int, 3>> faces;
  for (int j = 0; j + 1 < kSide; ++j)
    for (int i = 0; i + 1 < kSide; ++i) {
      faces.push_back({vertex(i, j + 1), vertex(i, j), vertex(i + 1, j + 1)});
      faces.push_back({vertex(i + 1, j + 1), vertex(i, j), vertex(i + 1, j)});
    }
  return faces;
}

void writeAsciiFaces(const std::string& path) {
  const auto faces = faceTriangles();
  std::ostringstream s;
  s << vertexHeader("ascii", int(faces.size()), "face", "uchar");
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) s << i << " " << j << " " << heightAt(i, j) << "\n";
  for (const auto& f : faces) s << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
  const std::string text = s.str();
  testing::writeBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
}

void writeAsciiStrips(const std::string& path) {
  const auto strip = stripIndices();
  std::ostringstream s;
  s << vertexHeader("ascii", 1, "tristrips", "int") << "";
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) s << i << " " << j << " " << heightAt(i, j) << "\n";
  s << strip.size();
  for (int v : strip) s << " " << v;
  s << "\n";
  const std::string text = s.str();
  testing::writeBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
}

template <class T>
void appendBigEndian(std::vector<uint8_t>& out, T value) {
  uint8_t bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (size_t k = 0; k < sizeof(T); ++k) out.push_back(bytes[sizeof(T) - 1 - k]);
}

void writeBigEndianStrips(const std::string& path) {
  const auto strip = stripIndices();
  const std::string header = vertexHeader("binary_big_endian", 1, "tristrips", "int");
  std::vector<uint8_t> bytes(header.begin(), header.end());
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i)
      for (float c : {float(i), float(j), heightAt(i, j)}) appendBigEndian(bytes, c);
  appendBigEndian(bytes, int32_t(strip.size()));
  for (int v : strip) appendBigEndian(bytes, int32_t(v));
  testing::writeBytes(path, bytes);
}

std::set<std::tuple<uint32_t, uint32_t, uint32_t>> voxelsOf(const TriangleMesh& mesh,
                                                            const VoxelGrid& grid) {
  auto surface = voxelizeSurface(mesh, grid);
  EXPECT_TRUE(surface) << surface.message();
  std::set<std::tuple<uint32_t, uint32_t, uint32_t>> voxels;
  if (surface)
    for (const SurfaceVoxel& v : surface->voxels) voxels.insert({v.x, v.y, v.z});
  return voxels;
}

TEST(PlyStrips, StripsVoxelizeLikeTheSameSurfaceAsTriangles) {
  TempDir dir;
  writeAsciiFaces(dir.file("faces.ply"));
  writeAsciiStrips(dir.file("strips.ply"));
  writeBigEndianStrips(dir.file("strips_be.ply"));
  auto faces = loadMesh(dir.file("faces.ply"));
  ASSERT_TRUE(faces) << faces.message();
  const size_t triangles = size_t(2 * (kSide - 1) * (kSide - 1));
  ASSERT_EQ(faces->triangleCount(), triangles);
  auto grid = fitGrid(meshBounds(*faces), 48);
  ASSERT_TRUE(grid) << grid.message();
  const auto expected = voxelsOf(*faces, *grid);
  EXPECT_GT(expected.size(), 1000u);
  for (const char* name : {"strips.ply", "strips_be.ply"}) {
    auto strips = loadMesh(dir.file(name));
    ASSERT_TRUE(strips) << name << ": " << strips.message();
    EXPECT_EQ(strips->triangleCount(), triangles) << name;
    EXPECT_EQ(strips->positions, faces->positions) << name;
    EXPECT_EQ(voxelsOf(*strips, *grid), expected) << name;
  }
}

TEST(PlyStrips, BadStripsNameTheFileAndItem) {
  TempDir dir;
  std::string text = vertexHeader("ascii", 1, "tristrips", "int");
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) text += std::to_string(i) + " " + std::to_string(j) + " 0\n";
  const std::string path = dir.file("bad.ply");
  const std::string outside = text + "4 0 1 2 169\n";
  testing::writeBytes(path, std::vector<uint8_t>(outside.begin(), outside.end()));
  auto mesh = loadMesh(path);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.message(), path +
                                ": element tristrips 0: vertex index 169 outside the 169 "
                                "vertices");
  // Beyond any integer: checked before it is cast (the cast was undefined).
  const std::string huge = text + "4 0 1 2 1e30\n";
  testing::writeBytes(path, std::vector<uint8_t>(huge.begin(), huge.end()));
  mesh = loadMesh(path);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.message(), path +
                                ": element tristrips 0: vertex index 1e+30 outside the 169 "
                                "vertices");
  const std::string shortList = text + "4 0 1 2\n";
  testing::writeBytes(path, std::vector<uint8_t>(shortList.begin(), shortList.end()));
  mesh = loadMesh(path);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.message(), path + ": element tristrips 0: data ends inside list vertex_indices");
}

// Faces assimp cannot make triangles of (here lines) leave far fewer triangles than the header
// declares: refused, not built from what is left.
TEST(PlyStrips, AMeshThatLostFacesIsRefused) {
  TempDir dir;
  const std::string path = dir.file("lines.ply");
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty "
      "float z\nelement face 5\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 "
      "0\n0 1 0\n1 1 0\n3 0 1 2\n2 0 1\n2 1 3\n2 3 2\n2 2 0\n";
  testing::writeBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
  auto mesh = loadMesh(path);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.message(), path +
                                ": the header declares 5 faces but only 1 triangles loaded; "
                                "refusing a mesh that lost faces");
}

}  // namespace
}  // namespace voxlink::geometry
