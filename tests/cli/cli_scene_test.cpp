// SPDX-License-Identifier: BSD-3-Clause
// `voxlink scene build` on the real meshes and particles, as a user runs it: the Cornell box's
// axis-aligned walls, a molecule beside a mesh, a CT volume with geometry inside it, and the
// rule that a scene holding only a volume keeps exactly the converter's voxels.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "format/gradient_codec.h"
#include "format/scene_index.h"
#include "format/validator.h"
#include "format/voxel_locator.h"
#include "format/voxlink_file.h"
#include "pack/open_file.h"
#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(CliScene, CornellBoxWallsAreOneVoxelThick) {
  VOXLINK_REQUIRE_DATA("mesh/mcguire_CornellBox-Original.obj");
  TempDir dir;
  const std::string scene = dir.file("cornell.scene.json");
  writeText(scene, R"({"grid": {"resolution": 128}, "objects": [{"type": "mesh", "file": ")" +
                       dataPath("mesh/mcguire_CornellBox-Original.obj") + R"("}]})");
  auto r = runVoxlink({"scene", "build", scene, "-o", dir.file("cornell.vxl")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("surface from 36 triangles"), std::string::npos) << r.out;
  auto f = pack::openFile(dir.file("cornell.vxl"));
  ASSERT_TRUE(f) << f.message();
  ASSERT_TRUE(format::validateFile(*f));
  EXPECT_TRUE(f->isScene());
  EXPECT_EQ(f->materials().size(), 9u);  // the MTL's eight materials + the default assimp adds
  // The floor lies on the grid's first voxel plane (fitGrid puts the bounds on voxel centres):
  // floor voxels (normal +-y) appear in layer y = 0 and none in layer y = 1.
  uint64_t layer0 = 0, layer1 = 0;
  const format::SceneIndex index(*f);
  format::VoxelLocator(*f).forEachVoxel([&](uint32_t, uint32_t y, uint32_t, uint64_t i) {
    const uint32_t word = index.surfaceWord(i);
    if (word == format::kNoSurface) return;
    if (std::abs(format::decodeGradient(format::surfaceNormal(word))[1]) < 0.999f) return;
    layer0 += y == 0;
    layer1 += y == 1;
  });
  EXPECT_GT(layer0, 100u * 100u);
  EXPECT_EQ(layer1, 0u);
}

TEST(CliScene, MoleculeBesideBunnyWithExactSpheres) {
  VOXLINK_REQUIRE_DATA("particles/biopython_2XHE.pdb");
  VOXLINK_REQUIRE_DATA("mesh/bunny_npm.obj");
  TempDir dir;
  const std::string scene = dir.file("mol.scene.json");
  writeText(scene, R"({"grid": {"resolution": 96}, "objects": [
      {"type": "particles", "file": ")" +
                       dataPath("particles/biopython_2XHE.pdb") + R"("},
      {"type": "mesh", "file": ")" +
                       dataPath("mesh/bunny_npm.obj") + R"(",
       "transform": {"scale": 4, "translate": [60, -60, 20]}}]})");
  auto r = runVoxlink({"scene", "build", scene, "-o", dir.file("mol.vxl")});
  ASSERT_EQ(r.status, 0) << r.err;
  auto f = pack::openFile(dir.file("mol.vxl"));
  ASSERT_TRUE(f) << f.message();
  ASSERT_TRUE(format::validateFile(*f));
  EXPECT_EQ(f->header().sphereCount, 6315u);
  EXPECT_GT(f->header().surfaceVoxelCount, 0u);
  auto info = runVoxlink({"info", dir.file("mol.vxl"), "--no-vdb"});
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_NE(info.out.find("6315 spheres"), std::string::npos) << info.out;
  auto render =
      runVoxlink({"render", dir.file("mol.vxl"), "-o", dir.file("mol.png"), "--size", "64x64"});
  EXPECT_EQ(render.status, 0) << render.err;
}

TEST(CliScene, VolumeOnlySceneKeepsTheConvertersVoxels) {
  VOXLINK_REQUIRE_DATA("ct/tooth_103x94x161_uint8.raw");
  TempDir dir;
  auto c = runVoxlink({"convert", dataPath("ct/tooth_103x94x161_uint8.raw"), "--dims", "103,94,161",
                       "--type", "u8", "--threshold", "60", "-o", dir.file("tooth.vxl"), "-q"});
  ASSERT_EQ(c.status, 0) << c.err;
  writeText(dir.file("t.scene.json"), R"({"objects": [{"type": "volume", "file": "tooth.vxl"}]})");
  auto r = runVoxlink({"scene", "build", dir.file("t.scene.json"), "-o", dir.file("scene.vxl")});
  ASSERT_EQ(r.status, 0) << r.err;
  auto a = pack::openFile(dir.file("tooth.vxl"));
  auto b = pack::openFile(dir.file("scene.vxl"));
  ASSERT_TRUE(a && b);
  EXPECT_FALSE(b->isScene());  // volume only: a version 1 file
  for (format::SectionId id : format::kRequiredSections) {
    if (id == format::SectionId::kMeta) continue;
    const auto x = a->sectionBytes(id), y = b->sectionBytes(id);
    EXPECT_TRUE(x.size() == y.size() && std::equal(x.begin(), x.end(), y.begin()))
        << format::sectionName(id);
  }
  EXPECT_EQ(a->header().valueMin, b->header().valueMin);
  EXPECT_EQ(a->header().valueMax, b->header().valueMax);
}

TEST(CliScene, GeometryInsideACtVolume) {
  VOXLINK_REQUIRE_DATA("ct/tooth_103x94x161_uint8.raw");
  VOXLINK_REQUIRE_DATA("mesh/bunny_npm.obj");
  TempDir dir;
  auto c = runVoxlink({"convert", dataPath("ct/tooth_103x94x161_uint8.raw"), "--dims", "103,94,161",
                       "--type", "u8", "--threshold", "60", "-o", dir.file("tooth.vxl"), "-q"});
  ASSERT_EQ(c.status, 0) << c.err;
  writeText(
      dir.file("t.scene.json"), R"({"objects": [{"type": "volume", "file": "tooth.vxl"},
      {"type": "mesh", "file": ")" + dataPath("mesh/bunny_npm.obj") +
                                    R"(", "transform": {"scale": 5, "translate": [50, 20, 80]}},
      {"type": "sphere", "center": [20, 20, 20], "radius": 8}]})");
  auto r = runVoxlink({"scene", "build", dir.file("t.scene.json"), "-o", dir.file("scene.vxl")});
  ASSERT_EQ(r.status, 0) << r.err;
  auto tooth = pack::openFile(dir.file("tooth.vxl"));
  auto f = pack::openFile(dir.file("scene.vxl"));
  ASSERT_TRUE(tooth && f);
  ASSERT_TRUE(format::validateFile(*f)) << format::validateFile(*f).message();
  EXPECT_EQ(f->header().volumeVoxelCount, tooth->voxelCount());
  EXPECT_GT(f->header().surfaceVoxelCount, 1000u);
  EXPECT_EQ(f->header().dims[0], 103u);
  // Every tooth voxel keeps its value in the scene.
  const format::VoxelLocator locator(*f);
  const format::SceneIndex index(*f);
  uint64_t checked = 0;
  format::VoxelLocator(*tooth).forEachVoxel([&](uint32_t x, uint32_t y, uint32_t z, uint64_t i) {
    const int64_t j = locator.find(x, y, z);
    ASSERT_GE(j, 0);
    const int64_t slot = index.volumeSlot(uint64_t(j));
    ASSERT_GE(slot, 0);
    ASSERT_EQ(f->value(uint64_t(slot)), tooth->value(i));
    ASSERT_EQ(f->gradientCodes()[uint64_t(slot)], tooth->gradientCodes()[i]);
    ++checked;
  });
  EXPECT_EQ(checked, tooth->voxelCount());
}

// Jensen's sphere box ray traced (mirror and glass spheres from the MTL, the scene's point light,
// shadow rays): the GL ray tracer against the float64 tracer, and bad effect options.
TEST(CliScene, SphereCornellBoxRayTraced) {
  VOXLINK_REQUIRE_DATA("mesh/mcguire_CornellBox-Sphere.obj");
  TempDir dir;
  const std::string scene = dir.file("spheres.scene.json");
  writeText(scene, R"({"grid": {"resolution": 96}, "objects": [{"type": "mesh", "file": ")" +
                       dataPath("mesh/mcguire_CornellBox-Sphere.obj") +
                       R"("}], "lights": [{"position": [0, 1.5, 0]}],
                       "camera": {"azimuth": 0, "elevation": 0, "fov": 40, "up": "y"}})");
  auto r = runVoxlink({"scene", "build", scene, "-o", dir.file("spheres.vxl")});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"render", dir.file("spheres.vxl"), "-o", dir.file("fx.png"), "--size", "64x64",
                  "--effects", "all", "--reference"});
  ASSERT_EQ(r.status, 0) << r.err;
  const size_t at = r.out.find("PSNR ");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_GE(std::stod(r.out.substr(at + 5)), 45.0) << r.out;
  for (const char* bad : {"mirror", "reflect,,x"}) {
    r = runVoxlink(
        {"render", dir.file("spheres.vxl"), "-o", dir.file("bad.png"), "--effects", bad});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("--effects"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  r = runVoxlink({"render", dir.file("spheres.vxl"), "-o", dir.file("bad.png"), "--effects", "all",
                  "--max-bounces", "99"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.png")));
}

// "N voxels (S surface from T triangles, P sphere from ..." -> {N, S, P}
std::array<uint64_t, 3> summaryCounts(const std::string& out) {
  std::array<uint64_t, 3> c{};
  const size_t at = out.find("], ");
  if (at == std::string::npos) return c;
  unsigned long long n = 0, surface = 0, tris = 0, sphere = 0;
  std::sscanf(out.c_str() + at + 3, "%llu voxels (%llu surface from %llu triangles, %llu sphere",
              &n, &surface, &tris, &sphere);
  return {n, surface, sphere};
}

TEST(CliScene, OverlappingObjectsShareVoxels) {
  TempDir dir;
  writeText(dir.file("quad.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
  // Two small spheres fix the bounds, so that both scenes get the same grid.
  const std::string grid = R"("grid": {"resolution": 64}, "objects": [
      {"type": "sphere", "center": [-0.2, -0.2, -0.3], "radius": 0.01},
      {"type": "sphere", "center": [1.6, 1.6, 0.3], "radius": 0.01}, )";
  writeText(dir.file("one.scene.json"), "{" + grid + R"({"type": "mesh", "file": "quad.obj"},
              {"type": "sphere", "center": [0.5, 0.5, 0], "radius": 0.1}]})");
  // The same quad twice, the second shifted by a sixth of a voxel, and a sphere crossing both.
  writeText(dir.file("two.scene.json"), "{" + grid + R"({"type": "mesh", "file": "quad.obj"},
              {"type": "mesh", "file": "quad.obj", "transform": {"translate": [0.005, 0, 0]}},
              {"type": "sphere", "center": [0.5, 0.5, 0], "radius": 0.1}]})");
  auto one = runVoxlink({"scene", "build", dir.file("one.scene.json"), "-o", dir.file("one.vxl")});
  ASSERT_EQ(one.status, 0) << one.err;
  auto two = runVoxlink({"scene", "build", dir.file("two.scene.json"), "-o", dir.file("two.vxl")});
  ASSERT_EQ(two.status, 0) << two.err;
  const auto c1 = summaryCounts(one.out), c2 = summaryCounts(two.out);
  EXPECT_GT(c1[1], 30u * 30u) << one.out;
  EXPECT_GT(c1[2], 0u) << one.out;
  // Voxels hold a surface fragment and sphere references together: fewer voxels than both.
  EXPECT_LT(c1[0], c1[1] + c1[2]) << one.out;
  // The overlapping quads merge per voxel: at most a column more, never twice the voxels.
  EXPECT_GE(c2[1], c1[1]) << two.out;
  EXPECT_LE(c2[1], c1[1] + 2 * 40u) << two.out;
  EXPECT_LT(c2[0], c2[1] + c2[2]) << two.out;
  auto f = pack::openFile(dir.file("two.vxl"));
  ASSERT_TRUE(f) << f.message();
  EXPECT_TRUE(format::validateFile(*f));
}

TEST(CliScene, BadInputIsOneLine) {
  TempDir dir;
  writeText(dir.file("bad.scene.json"),
            R"({"objects": [{"type": "mesh", "file": "missing.obj"}]})");
  auto r = runVoxlink({"scene", "build", dir.file("bad.scene.json"), "-o", dir.file("out.vxl")});
  EXPECT_NE(r.status, 0);
  // The scene file and the object come first, then the object's file.
  EXPECT_NE(r.err.find("bad.scene.json: objects[0]: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("missing.obj: no such file"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  std::filesystem::create_directory(dir.file("folder.obj"));
  writeText(dir.file("dir.scene.json"),
            R"({"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1},
                            {"type": "mesh", "file": "folder.obj"}]})");
  r = runVoxlink({"scene", "build", dir.file("dir.scene.json"), "-o", dir.file("out.vxl")});
  EXPECT_NE(r.err.find("dir.scene.json: objects[1]: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("folder.obj: not a regular file"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.vxl")));
  writeText(dir.file("nan.obj"), "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  writeText(dir.file("nan.scene.json"), R"({"objects": [{"type": "mesh", "file": "nan.obj"}]})");
  r = runVoxlink({"scene", "build", dir.file("nan.scene.json"), "-o", dir.file("out.vxl")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("nan.obj"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("line 3"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.vxl")));
  // The output may not be one of the scene's inputs.
  writeText(dir.file("self.scene.json"),
            R"({"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}]})");
  r = runVoxlink(
      {"scene", "build", dir.file("self.scene.json"), "-o", dir.file("self.scene.json")});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("self.scene.json"), std::string::npos) << r.err;
  writeText(dir.file("empty.scene.json"), R"({"objects": []})");
  r = runVoxlink({"scene", "build", dir.file("empty.scene.json"), "-o", dir.file("out.vxl")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("no geometry and no volume"), std::string::npos) << r.err;
}

// Trilinear sampling is for volume files: a scene asked for it is refused in one line naming the
// file and the option, and no image is written (before: "voxlink: voxlink: scenes ...", no file).
TEST(CliScene, TrilinearSamplingOfASceneNamesTheFileAndOption) {
  TempDir dir;
  writeText(dir.file("ball.scene.json"),
            R"({"grid": {"resolution": 16},
                "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}]})");
  auto r = runVoxlink({"scene", "build", dir.file("ball.scene.json"), "-o", dir.file("ball.vxl")});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"render", dir.file("ball.vxl"), "--sampling", "trilinear", "--size", "16x16",
                  "-o", dir.file("ball.png")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("ball.vxl: --sampling trilinear: scenes"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("voxlink: voxlink:"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("ball.png")));
}

// A resolution the machine cannot hold is refused before voxelizing, naming the field to change,
// instead of working for minutes and dying of std::bad_alloc or the OOM killer.
TEST(CliScene, ResolutionBeyondMemoryIsRefusedAtOnce) {
  VOXLINK_REQUIRE_DATA("mesh/c3dtm_stanford-bunny.obj");
  TempDir dir;
  writeText(dir.file("bunny.scene.json"),
            R"({"grid": {"resolution": 60000}, "objects": [{"type": "mesh", "file": ")" +
                dataPath("mesh/c3dtm_stanford-bunny.obj") + R"("}]})");
  // About 6 billion surface voxels: no machine that runs these tests holds their 600 GB.
  auto r = runVoxlink({"scene", "build", dir.file("bunny.scene.json"), "-o", dir.file("out.vxl")});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("bunny.scene.json: grid.resolution 60000: building needs about "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("lower grid.resolution or --resolution"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.vxl")));
  // The same file at a resolution that fits builds.
  r = runVoxlink({"scene", "build", dir.file("bunny.scene.json"), "-o", dir.file("out.vxl"),
                  "--resolution", "64"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("out.vxl")));
}

}  // namespace
}  // namespace voxlink::testing
