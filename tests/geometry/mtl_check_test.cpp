// SPDX-License-Identifier: BSD-3-Clause
// loadMesh on OBJ files whose MTL holds statements assimp 5.2.5 writes through a null material
// (texture maps and anisotropy before the first newmtl: a SEGV, docs/fuzzing.md), and on the
// statements next to them that assimp reads safely and that must still load.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "geometry/mesh_loader.h"
#include "tests/support/test_util.h"

namespace voxlink::geometry {
namespace {

using testing::TempDir;

void writeText(const std::string& path, const std::string& text) {
  testing::writeBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
}

const std::string kTriangleObj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
// assimp fails the whole load on an MTL file under 8 bytes, before reading its statements.
const std::string kPadding = "# a material library\n";

Result<TriangleMesh> loadWithMtl(const TempDir& dir, const std::string& mtl) {
  writeText(dir.file("m.obj"), kTriangleObj);
  writeText(dir.file("m.mtl"), mtl);
  return loadMesh(dir.file("m.obj"));
}

void expectRefused(const std::string& mtl, const std::string& expected) {
  TempDir dir;
  auto mesh = loadWithMtl(dir, mtl);
  ASSERT_FALSE(mesh) << "loaded: " << mtl;
  EXPECT_EQ(mesh.code(), ErrorCode::kCorrupt);
  EXPECT_NE(mesh.message().find(dir.file("m.mtl") + ": " + expected), std::string::npos)
      << mesh.message();
  EXPECT_NE(mesh.message().find("m.obj"), std::string::npos) << mesh.message();
  EXPECT_EQ(mesh.message().find('\n'), std::string::npos) << mesh.message();
}

TEST(MtlCheck, FuzzFindingMinimised) {
  // The fuzz input cut down by delta debugging: NUL bytes end lines for assimp, so the `a` is a
  // statement of its own, and the empty value after it is written as 0 into no material.
  expectRefused(std::string("\x01\0\0a\0\0#\r", 8), "line 1: 'a' (anisotropy) before the first");
}

TEST(MtlCheck, AnisotropyBeforeNewmtl) {
  expectRefused(kPadding + "a 1\nnewmtl red\nKd 1 0 0\n", "line 2: 'a' (anisotropy)");
  expectRefused(kPadding + "x\r\n  anisor 0.5\n", "line 3: 'anisor' (anisotropy)");
  expectRefused(kPadding + "x\fa 1\n", "line 2: 'a' (anisotropy)");  // form feed ends a line
}

TEST(MtlCheck, EveryTextureMapBeforeNewmtl) {
  for (const char* keyword :
       {"map_Kd", "map_Ka", "map_Ks", "map_d", "map_Ke", "map_emissive", "map_bump", "bump",
        "map_Kn", "norm", "map_disp", "disp", "map_ns", "map_Pr", "map_Pm", "map_Ps"}) {
    SCOPED_TRACE(keyword);
    expectRefused(kPadding + "\t" + keyword + " red.png\nnewmtl red\n",
                  std::string("line 2: '") + keyword + "' (texture map) before the first newmtl");
  }
  // assimp picks the texture reader by the first byte, then ignores case.
  expectRefused(kPadding + "mAP_kd red.png\n", "line 2: 'mAP_kd' (texture map)");
  expectRefused(kPadding + "NoRM red.png\n", "line 2: 'NoRM' (texture map)");
}

TEST(MtlCheck, TheSameStatementsAfterNewmtlLoad) {
  TempDir dir;
  auto mesh = loadWithMtl(dir, kPadding +
                                   "newmtl red\nKd 1 0 0\na 1\nmap_Kd red.png\nbump b.png\n"
                                   "norm n.png\ndisp d.png\n");
  ASSERT_TRUE(mesh) << mesh.message();
  EXPECT_EQ(mesh->triangleCount(), 1u);
  ASSERT_EQ(mesh->triangleMaterials.size(), 1u);
  EXPECT_EQ(mesh->materials.at(mesh->triangleMaterials[0]).name, "red");
  EXPECT_FLOAT_EQ(mesh->materials.at(mesh->triangleMaterials[0]).color[0], 1.0f);
}

TEST(MtlCheck, StatementsAssimpSkipsBeforeNewmtlStillLoad) {
  // Colours and scalars before newmtl assimp drops; `refl` it ignores; an upper-case first byte
  // or a blank that opens the file reaches no texture reader. None of them is refused.
  for (const std::string& mtl :
       {kPadding + "Kd 1 1 1\nNs 10\nNi 1.5\nd 0.5\nTr 0.5\nillum 2\nPr 1\nnewmtl red\n",
        kPadding + "refl r.png\nnewmtl red\n", kPadding + "MAP_KD x.png\nNORM n.png\nnewmtl red\n",
        " map_Kd x.png\n" + kPadding + "newmtl red\n"}) {
    SCOPED_TRACE(mtl);
    TempDir dir;
    auto mesh = loadWithMtl(dir, mtl);
    ASSERT_TRUE(mesh) << mesh.message();
    EXPECT_EQ(mesh->triangleCount(), 1u);
  }
}

TEST(MtlCheck, FallbackMtlIsCheckedToo) {
  // The OBJ names a missing library; loadMesh falls back to the MTL named like the OBJ.
  TempDir dir;
  writeText(dir.file("scene.obj"), "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  writeText(dir.file("scene.mtl"), kPadding + "map_Kd x.png\n");
  auto mesh = loadMesh(dir.file("scene.obj"));
  ASSERT_FALSE(mesh);
  EXPECT_NE(mesh.message().find(dir.file("scene.mtl") + ": line 2: 'map_Kd'"), std::string::npos)
      << mesh.message();
}

TEST(MtlCheck, LibraryWithoutMtlExtensionIsChecked) {
  TempDir dir;
  writeText(dir.file("scene.obj"), "mtllib materials.txt\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  writeText(dir.file("materials.txt"), kPadding + "bump b.png\n");
  auto mesh = loadMesh(dir.file("scene.obj"));
  ASSERT_FALSE(mesh);
  EXPECT_NE(mesh.message().find(dir.file("materials.txt") + ": line 2: 'bump'"), std::string::npos)
      << mesh.message();
}

// assimp drops a UTF-8 byte order mark before it reads a library (BaseImporter::TextFileToBuffer),
// so the statement after the mark opens the file. Before the check skipped it too, a marked
// library was refused for map_Kd after its first-line newmtl, and a marked map_Kd on the first
// line passed the check and crashed assimp (SIGSEGV).
const std::string kByteOrderMark = "\xEF\xBB\xBF";

TEST(MtlCheck, ByteOrderMarkedLibraryWithNewmtlFirstLoads) {
  TempDir dir;
  auto mesh = loadWithMtl(dir, kByteOrderMark + "newmtl red\nKd 1 0 0\nmap_Kd red.png\n");
  ASSERT_TRUE(mesh) << mesh.message();
  ASSERT_EQ(mesh->triangleMaterials.size(), 1u);
  EXPECT_EQ(mesh->materials.at(mesh->triangleMaterials[0]).name, "red");
  EXPECT_FLOAT_EQ(mesh->materials.at(mesh->triangleMaterials[0]).color[0], 1.0f);
}

TEST(MtlCheck, ByteOrderMarkedTextureMapOnTheFirstLineIsRefused) {
  expectRefused(kByteOrderMark + "map_Kd red.png\nnewmtl red\n",
                "line 1: 'map_Kd' (texture map) before the first newmtl");
  expectRefused(kByteOrderMark + "a 1\nnewmtl red\n", "line 1: 'a' (anisotropy)");
}

}  // namespace
}  // namespace voxlink::geometry
