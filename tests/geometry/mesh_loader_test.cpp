// SPDX-License-Identifier: BSD-3-Clause
// loadMesh on the real meshes in ../shared/data/mesh and on small files written here.
#include "geometry/mesh_loader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "tests/support/test_util.h"

namespace voxlink::geometry {
namespace {

using testing::dataPath;
using testing::TempDir;

void writeText(const std::string& path, const std::string& text) {
  testing::writeBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
}

const Material* findMaterial(const TriangleMesh& mesh, const std::string& name) {
  for (const Material& m : mesh.materials)
    if (m.name == name) return &m;
  return nullptr;
}

TEST(MeshLoader, BunnyObjAndAsciiPlyAgree) {
  VOXLINK_REQUIRE_DATA("mesh/c3dtm_stanford-bunny.obj");
  VOXLINK_REQUIRE_DATA("mesh/vtk_bunny.ply");
  auto obj = loadMesh(dataPath("mesh/c3dtm_stanford-bunny.obj"));
  auto ply = loadMesh(dataPath("mesh/vtk_bunny.ply"));
  ASSERT_TRUE(obj) << obj.message();
  ASSERT_TRUE(ply) << ply.message();
  EXPECT_EQ(obj->triangleCount(), 69451u);
  EXPECT_EQ(ply->triangleCount(), 69451u);
  EXPECT_EQ(ply->vertexCount(), 35947u);  // PLY keeps its shared vertices
  const Bounds3 a = meshBounds(*obj), b = meshBounds(*ply);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(a.min[axis], b.min[axis], 1e-5f);
    EXPECT_NEAR(a.max[axis], b.max[axis], 1e-5f);
  }
  EXPECT_NEAR(b.max[1], 0.187321f, 1e-6f);  // the ear tip, from the PLY's text
  EXPECT_EQ(obj->triangleMaterials.size(), obj->triangleCount());
}

TEST(MeshLoader, HorseBigEndianPly) {
  VOXLINK_REQUIRE_DATA("mesh/vtk_horse.ply");
  auto mesh = loadMesh(dataPath("mesh/vtk_horse.ply"));
  ASSERT_TRUE(mesh) << mesh.message();
  EXPECT_EQ(mesh->vertexCount(), 48485u);
  EXPECT_EQ(mesh->triangleCount(), 96966u);
  const Bounds3 b = meshBounds(*mesh);
  // Read with the wrong byte order the floats would be huge or tiny; the horse is ~0.18 long.
  EXPECT_NEAR(b.max[1] - b.min[1], 0.183341f, 1e-5f);
}

TEST(MeshLoader, DragonLittleEndianPly) {
  VOXLINK_REQUIRE_DATA("mesh/stanford_dragon_decimated.ply");
  auto mesh = loadMesh(dataPath("mesh/stanford_dragon_decimated.ply"));
  ASSERT_TRUE(mesh) << mesh.message();
  EXPECT_EQ(mesh->vertexCount(), 11429u);
  EXPECT_EQ(mesh->triangleCount(), 22866u);
}

TEST(MeshLoader, CornellBoxOriginalMaterials) {
  VOXLINK_REQUIRE_DATA("mesh/mcguire_CornellBox-Original.obj");
  // The OBJ names CornellBox-Original.mtl; the file beside it is mcguire_CornellBox-Original.mtl.
  auto mesh = loadMesh(dataPath("mesh/mcguire_CornellBox-Original.obj"));
  ASSERT_TRUE(mesh) << mesh.message();
  EXPECT_EQ(mesh->triangleCount(), 36u);  // 18 quads, negative indices
  const Material* light = findMaterial(*mesh, "light");
  ASSERT_NE(light, nullptr);
  EXPECT_FLOAT_EQ(light->emission[0], 17.0f);
  EXPECT_FLOAT_EQ(light->emission[1], 12.0f);
  EXPECT_FLOAT_EQ(light->emission[2], 4.0f);
  const Material* left = findMaterial(*mesh, "leftWall");
  ASSERT_NE(left, nullptr);
  EXPECT_FLOAT_EQ(left->color[0], 0.63f);
  EXPECT_FLOAT_EQ(left->refractiveIndex, 1.0f);  // Ni 1.5 but illum 2: does not refract
  // The light's two triangles carry the light's material.
  size_t lightTriangles = 0;
  for (uint16_t m : mesh->triangleMaterials) lightTriangles += mesh->materials[m].name == "light";
  EXPECT_EQ(lightTriangles, 2u);
}

TEST(MeshLoader, CornellBoxSphereMirrorAndGlass) {
  VOXLINK_REQUIRE_DATA("mesh/mcguire_CornellBox-Sphere.obj");
  auto mesh = loadMesh(dataPath("mesh/mcguire_CornellBox-Sphere.obj"));
  ASSERT_TRUE(mesh) << mesh.message();
  const Material* mirror = findMaterial(*mesh, "leftSphere");  // illum 5, Ks 0.95
  const Material* glass = findMaterial(*mesh, "rightSphere");  // illum 7, Ni 2.5, Ks 0.3
  ASSERT_NE(mirror, nullptr);
  ASSERT_NE(glass, nullptr);
  EXPECT_NEAR(mirror->reflectivity, 0.95f, 1e-6f);
  EXPECT_FLOAT_EQ(mirror->transmission, 0.0f);
  EXPECT_FLOAT_EQ(glass->refractiveIndex, 2.5f);
  EXPECT_FLOAT_EQ(glass->transmission, 1.0f);
  EXPECT_NEAR(glass->reflectivity, 0.3f, 1e-6f);
  const Material* light = findMaterial(*mesh, "light");
  ASSERT_NE(light, nullptr);
  EXPECT_FLOAT_EQ(light->emission[0], 10.0f);
  EXPECT_EQ(mesh->normals.size(), mesh->positions.size());  // the file has vn records
}

TEST(MeshLoader, PolygonsAndNegativeIndices) {
  TempDir dir;
  writeText(dir.file("p.obj"),
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0.5 1.5 0\nv 0 1 0\n"
            "f -5 -4 -3 -2 -1\n"  // a pentagon -> 3 triangles
            "v 0 0 1\nv 1 0 1\nv 0 1 1\nf 6 7 8\n");
  auto mesh = loadMesh(dir.file("p.obj"));
  ASSERT_TRUE(mesh) << mesh.message();
  EXPECT_EQ(mesh->triangleCount(), 4u);
  const Bounds3 b = meshBounds(*mesh);
  EXPECT_FLOAT_EQ(b.max[1], 1.5f);
  EXPECT_FLOAT_EQ(b.max[2], 1.0f);
}

// A two-triangle binary PLY with an extra float and an extra uchar per vertex.
std::vector<uint8_t> binaryPly(bool bigEndian) {
  std::string header = std::string("ply\nformat ") +
                       (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                       " 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                       "property float z\nproperty float confidence\nproperty uchar red\n"
                       "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
  std::vector<uint8_t> out(header.begin(), header.end());
  auto put = [&](const void* p, size_t n) {
    const uint8_t* b = static_cast<const uint8_t*>(p);
    for (size_t i = 0; i < n; ++i) out.push_back(b[bigEndian ? n - 1 - i : i]);
  };
  const float v[4][4] = {{0, 0, 0, 0.5f}, {2, 0, 0, 0.5f}, {2, 3, 0, 0.5f}, {0, 3, 4, 0.5f}};
  for (const auto& vertex : v) {
    for (float f : vertex) put(&f, 4);
    out.push_back(7);
  }
  const int32_t faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (const auto& face : faces) {
    out.push_back(3);
    for (int32_t i : face) put(&i, 4);
  }
  return out;
}

TEST(MeshLoader, BinaryPlyBothByteOrders) {
  TempDir dir;
  for (bool bigEndian : {false, true}) {
    const std::string path = dir.file(bigEndian ? "be.ply" : "le.ply");
    testing::writeBytes(path, binaryPly(bigEndian));
    auto mesh = loadMesh(path);
    ASSERT_TRUE(mesh) << mesh.message();
    EXPECT_EQ(mesh->triangleCount(), 2u);
    const Bounds3 b = meshBounds(*mesh);
    EXPECT_FLOAT_EQ(b.max[0], 2.0f);
    EXPECT_FLOAT_EQ(b.max[1], 3.0f);
    EXPECT_FLOAT_EQ(b.max[2], 4.0f);
  }
}

// Blanks after `end_header` (files written by hand; assimp reads them): the header check
// accepts them and the binary data still starts after the line end.
TEST(MeshLoader, BlanksAfterEndHeader) {
  TempDir dir;
  std::vector<uint8_t> binary = binaryPly(false);
  const std::string mark = "end_header";
  auto at = std::search(binary.begin(), binary.end(), mark.begin(), mark.end());
  ASSERT_NE(at, binary.end());
  binary.insert(at + mark.size(), {' ', '\t', ' '});
  testing::writeBytes(dir.file("blanks.ply"), binary);
  auto mesh = loadMesh(dir.file("blanks.ply"));
  ASSERT_TRUE(mesh) << mesh.message();
  EXPECT_EQ(mesh->triangleCount(), 2u);
  EXPECT_FLOAT_EQ(meshBounds(*mesh).max[2], 4.0f);
  writeText(dir.file("blanks-ascii.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
            "property float y\nproperty float z\nelement face 1\n"
            "property list uchar int vertex_indices\nend_header  \r\n"
            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  auto ascii = loadMesh(dir.file("blanks-ascii.ply"));
  ASSERT_TRUE(ascii) << ascii.message();
  EXPECT_EQ(ascii->triangleCount(), 1u);
}

TEST(MeshLoader, AsciiStl) {
  TempDir dir;
  writeText(
      dir.file("t.stl"),
      "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 2 0 0\n"
      "   vertex 0 3 0\n  endloop\n endfacet\n facet normal 0 0 -1\n  outer loop\n"
      "   vertex 0 0 1\n   vertex 0 3 1\n   vertex 2 0 1\n  endloop\n endfacet\nendsolid t\n");
  auto mesh = loadMesh(dir.file("t.stl"));
  ASSERT_TRUE(mesh) << mesh.message();
  EXPECT_EQ(mesh->triangleCount(), 2u);
  const Bounds3 b = meshBounds(*mesh);
  EXPECT_FLOAT_EQ(b.max[1], 3.0f);
  EXPECT_FLOAT_EQ(b.max[2], 1.0f);
}

TEST(MeshLoaderErrors, MissingFile) {
  auto mesh = loadMesh("/nonexistent/mesh.obj");
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.code(), ErrorCode::kIo);
  EXPECT_NE(mesh.message().find("/nonexistent/mesh.obj"), std::string::npos);
}

TEST(MeshLoaderErrors, Unparseable) {
  TempDir dir;
  writeText(dir.file("bad.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1\n");
  auto mesh = loadMesh(dir.file("bad.ply"));
  ASSERT_FALSE(mesh);
  EXPECT_NE(mesh.message().find("bad.ply"), std::string::npos) << mesh.message();
  EXPECT_EQ(mesh.message().find('\n'), std::string::npos);
}

TEST(MeshLoaderErrors, PlyFormatThatIsNoPlyFormatNamesTheField) {
  TempDir dir;
  writeText(dir.file("middle.ply"),
            "ply\nformat binary_middle_endian 1.0\nelement vertex 3\nproperty float x\n"
            "property float y\nproperty float z\nend_header\n");
  auto mesh = loadMesh(dir.file("middle.ply"));
  ASSERT_FALSE(mesh);
  EXPECT_NE(mesh.message().find("middle.ply: line 2: format 'binary_middle_endian'"),
            std::string::npos)
      << mesh.message();
}

TEST(MeshLoaderErrors, NoTriangles) {
  TempDir dir;
  writeText(dir.file("points.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n");
  auto mesh = loadMesh(dir.file("points.obj"));
  ASSERT_FALSE(mesh);
  EXPECT_NE(mesh.message().find("points.obj"), std::string::npos) << mesh.message();
}

TEST(MeshLoaderErrors, NonFiniteObjVertexNamesTheLine) {
  TempDir dir;
  writeText(dir.file("nan.obj"), "# a comment\nv 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
  auto mesh = loadMesh(dir.file("nan.obj"));
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.code(), ErrorCode::kNonFinite) << mesh.message();
  EXPECT_NE(mesh.message().find("nan.obj: line 3"), std::string::npos) << mesh.message();
}

TEST(MeshLoaderErrors, NonFinitePlyVertex) {
  TempDir dir;
  writeText(dir.file("inf.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0\n1 0 inf\n0 1 0\n3 0 1 2\n");
  auto mesh = loadMesh(dir.file("inf.ply"));
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.code(), ErrorCode::kNonFinite) << mesh.message();
  EXPECT_NE(mesh.message().find("inf.ply: vertex 1"), std::string::npos) << mesh.message();
}

TEST(MeshLoaderErrors, TriangleLimit) {
  TempDir dir;
  writeText(dir.file("two.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
  MeshLoadOptions options;
  options.maxTriangles = 1;
  auto mesh = loadMesh(dir.file("two.obj"), options);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.code(), ErrorCode::kTooLarge);
  EXPECT_NE(mesh.message().find("two.obj"), std::string::npos);
  EXPECT_TRUE(loadMesh(dir.file("two.obj")));
}

// Counts a file cannot hold are refused from the header, naming the element, instead of
// assimp reserving them and failing with a bare std::bad_alloc.
TEST(MeshLoaderErrors, CountsBeyondTheFileNameTheElement) {
  TempDir dir;
  const std::string binaryHeader =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  writeText(dir.file("vertices.ply"), binaryHeader + std::string(40, '\0'));
  auto mesh = loadMesh(dir.file("vertices.ply"));
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.code(), ErrorCode::kCorrupt);
  EXPECT_NE(mesh.message().find("vertices.ply: element vertex 4000000000: needs at least "
                                "4000000000 x 12 bytes, but the file has 40 after its header"),
            std::string::npos)
      << mesh.message();
  writeText(dir.file("faces.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 2000000000\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  mesh = loadMesh(dir.file("faces.ply"));
  ASSERT_FALSE(mesh);
  EXPECT_NE(mesh.message().find("faces.ply: element face 2000000000: "), std::string::npos)
      << mesh.message();
  writeText(dir.file("counts.off"), "OFF\n4000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  mesh = loadMesh(dir.file("counts.off"));
  ASSERT_FALSE(mesh);
  EXPECT_NE(mesh.message().find("counts.off: header claims 4000000000 vertices and 1 faces"),
            std::string::npos)
      << mesh.message();
  writeText(dir.file("short.off"), "OFF 4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n");
  mesh = loadMesh(dir.file("short.off"));
  ASSERT_FALSE(mesh);
  EXPECT_NE(mesh.message().find("short.off: face 1: missing (the header claims 2)"),
            std::string::npos)
      << mesh.message();
}

// The count check's lower bound holds for the tightest valid files: one-character ASCII values
// with no line end after the last one (17 bytes for three vertices of three values).
TEST(MeshLoaderErrors, SecondElementOfANameIsRefused) {
  // assimp 5.2 wrote the second element's 3000 vertices past an array sized for the first's one.
  TempDir dir;
  std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nelement vertex 3000\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n";
  for (int i = 0; i < 3000; ++i) ply += std::to_string(i) + " 1 0\n";
  writeText(dir.file("twice.ply"), ply + "3 0 1 2\n");
  auto mesh = loadMesh(dir.file("twice.ply"));
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.code(), ErrorCode::kCorrupt);
  EXPECT_NE(mesh.message().find("twice.ply: line 7: element vertex is declared a second time"),
            std::string::npos)
      << mesh.message();
}

// A bad element count names its line, as the other header refusals do (before: the file and the
// field but no line).
TEST(MeshLoaderErrors, PlyElementCountThatIsNoNumberNamesTheLine) {
  TempDir dir;
  writeText(dir.file("count.ply"),
            "ply\nformat ascii 1.0\nelement vertex 1e3\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n0 0 0\n");
  auto count = loadMesh(dir.file("count.ply"));
  ASSERT_FALSE(count);
  EXPECT_NE(count.message().find("count.ply: line 3: element vertex: count '1e3' is not a whole"),
            std::string::npos)
      << count.message();
}

TEST(MeshLoader, TightestAsciiPlyPassesTheCountCheck) {
  TempDir dir;
  writeText(dir.file("tight.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n0 0 0\n1 0 0\n0 1 0");
  auto mesh = loadMesh(dir.file("tight.ply"));
  ASSERT_FALSE(mesh);  // points only
  EXPECT_EQ(mesh.message().find("needs at least"), std::string::npos) << mesh.message();
  writeText(dir.file("short.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n0 0 0\n1 0 0\n0 1");
  mesh = loadMesh(dir.file("short.ply"));
  ASSERT_FALSE(mesh);
  EXPECT_NE(mesh.message().find("short.ply: element vertex 3: needs at least 3 x 6 bytes, but "
                                "the file has 15 after its header"),
            std::string::npos)
      << mesh.message();
}

// assimp clamps an OFF face index past the vertices to the last vertex and loads a wrong mesh.
TEST(MeshLoaderErrors, OffIndexPastTheVerticesIsRefused) {
  TempDir dir;
  writeText(dir.file("index.off"),
            "OFF\n# three vertices\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n\n3 0 1 7\n");
  auto mesh = loadMesh(dir.file("index.off"));
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.code(), ErrorCode::kCorrupt);
  EXPECT_NE(mesh.message().find("index.off: line 8: face 0: vertex index 7 outside the 3 vertices"),
            std::string::npos)
      << mesh.message();
  // The same file with a valid index, a quad and a comment loads: three triangles.
  writeText(dir.file("good.off"),
            "OFF\n# three vertices\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n\n3 0 1 2\n4 0 1 3 2\n");
  mesh = loadMesh(dir.file("good.off"));
  ASSERT_TRUE(mesh) << mesh.message();
  EXPECT_EQ(mesh->triangleCount(), 3u);
}

}  // namespace
}  // namespace voxlink::geometry
