// SPDX-License-Identifier: BSD-3-Clause
// `mpirun -n N voxlink scene build ...` (docs/scale.md, "Scene builds"): each rank voxelizes the
// triangles and spheres of its brick layers, rank 0 merges and writes; the file is byte for byte
// the one process's for 1 to 4 ranks, on real meshes, a PDB, a Cornell box with materials, a CT
// volume with geometry, and grids whose brick layers do not divide among the ranks. Faults: a
// rank that cannot load an input, a rank that sees other inputs, an output rank 0 cannot write.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include "tests/mpi/mpi_launch.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

struct SceneCase {
  const char* name;
  const char* data;  // one real file the scene needs
  std::string json;  // "@name" stands for dataPath(name)
  std::vector<std::string> options;
};

// Test names and failure messages show the case's name, not its bytes.
void PrintTo(const SceneCase& c, std::ostream* os) { *os << c.name; }

std::string expand(std::string json) {
  for (size_t at; (at = json.find('@')) != std::string::npos;) {
    const size_t end = json.find('"', at);
    json.replace(at, end - at, dataPath(json.substr(at + 1, end - at - 1)));
  }
  return json;
}

std::vector<SceneCase> sceneCases() {
  return {
      // 18 quads with MTL materials and an emissive light; 128 along x: 16 brick layers.
      {"CornellBoxWithMaterials",
       "mesh/mcguire_CornellBox-Original.obj",
       R"({"grid": {"resolution": 128, "brick": 8}, "objects": [
           {"type": "mesh", "file": "@mesh/mcguire_CornellBox-Original.obj"}]})",
       {}},
      // The full bunny (69k triangles) at 160.
      {"Bunny",
       "mesh/c3dtm_stanford-bunny.obj",
       R"({"grid": {"resolution": 160}, "objects": [
           {"type": "mesh", "file": "@mesh/c3dtm_stanford-bunny.obj"}]})",
       {}},
      // 6,468 atoms as spheres, one material per element; 16^3 bricks.
      {"ProteinSpheres",
       "particles/biopython_7DDO.pdb",
       R"({"grid": {"resolution": 120, "brick": 16}, "objects": [
           {"type": "particles", "file": "@particles/biopython_7DDO.pdb"}]})",
       {}},
      // Mesh, PDB and a sphere in one grid: surface fragments and sphere lists in shared voxels.
      {"MeshProteinAndSphere",
       "particles/biopython_2XHE.pdb",
       R"({"grid": {"resolution": 100}, "materials": {"porcelain": {"color": [0.85, 0.82, 0.78]}},
           "objects": [
           {"type": "particles", "file": "@particles/biopython_2XHE.pdb"},
           {"type": "mesh", "file": "@mesh/c3dtm_stanford-bunny.obj",
            "transform": {"scale": 500, "translate": [80, -100, 20]}, "material": "porcelain"},
           {"type": "sphere", "center": [80, -40, -40], "radius": 18, "material": "porcelain"}]})",
       {}},
      // A volume (the 41^3 nucleon, 41 slices: 6 layers of 8, the last one a single slice)
      // converted by rank 0, with a mesh and a sphere placed inside it, in its world coordinates.
      {"VolumeMeshAndSphere",
       "volume/voreen_nucleon/nucleon.nrrd",
       R"({"objects": [
           {"type": "volume", "file": "@volume/voreen_nucleon/nucleon.nrrd", "threshold": 60},
           {"type": "mesh", "file": "@mesh/bunny_npm.obj",
            "transform": {"scale": 3, "translate": [20, 5, 20]}},
           {"type": "sphere", "center": [10, 30, 12], "radius": 7}]})",
       {}},
      // 2 brick layers (40x21x26 in bricks of 16) on up to 4 ranks: ranks with no layer at all.
      {"FewerLayersThanRanks",
       "mesh/c3dtm_teapot.obj",
       R"({"grid": {"resolution": 40, "brick": 16}, "objects": [
           {"type": "mesh", "file": "@mesh/c3dtm_teapot.obj"}]})",
       {}},
      // --resolution and --brick from the command line: 65x70x37 in bricks of 4, 10 layers.
      {"LayersThatDoNotDivide",
       "mesh/c3dtm_fandisk.obj",
       R"({"objects": [{"type": "mesh", "file": "@mesh/c3dtm_fandisk.obj"}]})",
       {"--resolution", "70", "--brick", "4"}},
      // Fragment lists (format version 2.1): planes of the bunny, triangle references of the
      // fandisk, each voxel's list made on the rank of its slab.
      {"BunnyPlanes",
       "mesh/c3dtm_stanford-bunny.obj",
       R"({"grid": {"resolution": 96}, "objects": [
           {"type": "mesh", "file": "@mesh/c3dtm_stanford-bunny.obj"}]})",
       {"--surface", "planes"}},
      {"FandiskTriangles",
       "mesh/c3dtm_fandisk.obj",
       R"({"objects": [{"type": "mesh", "file": "@mesh/c3dtm_fandisk.obj"}]})",
       {"--resolution", "70", "--brick", "4", "--surface", "triangles"}},
  };
}

class SceneSameBytes : public ::testing::TestWithParam<SceneCase> {};

TEST_P(SceneSameBytes, AsOneProcess) {
  const SceneCase& c = GetParam();
  VOXLINK_REQUIRE_DATA(c.data);
  TempDir dir;
  const std::string scene = dir.file("s.scene.json");
  writeText(scene, expand(c.json));
  auto args = [&](const std::string& out) {
    std::vector<std::string> a = {"scene", "build", scene, "-q", "-o", dir.file(out)};
    a.insert(a.end(), c.options.begin(), c.options.end());
    return a;
  };
  const Launch plain = runPlain(args("plain.vxl"));
  ASSERT_EQ(plain.status, 0) << plain.err;
  const Launch valid = runPlain({"validate", dir.file("plain.vxl"), "-q"});
  ASSERT_EQ(valid.status, 0) << valid.err;
  const std::vector<uint8_t> expected = readBytes(dir.file("plain.vxl"));
  for (int ranks = 1; ranks <= 4; ++ranks) {
    const std::string out = "r" + std::to_string(ranks) + ".vxl";
    const Launch r = runRanks(ranks, args(out));
    ASSERT_EQ(r.status, 0) << ranks << " ranks: " << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_TRUE(readBytes(dir.file(out)) == expected) << ranks << " ranks wrote other bytes";
  }
  // Without -q rank 0 alone prints the summary line.
  const Launch loud = runRanks(3, {"scene", "build", scene, "-o", dir.file("loud.vxl")});
  ASSERT_EQ(loud.status, 0) << loud.err;
  EXPECT_EQ(lineCount(loud.out), 1u) << loud.out;
}

INSTANTIATE_TEST_SUITE_P(MpiScene, SceneSameBytes, ::testing::ValuesIn(sceneCases()),
                         [](const auto& p) { return std::string(p.param.name); });

// Rank 1 of 3 is given a scene whose mesh does not load (as a node that sees a damaged copy).
TEST(MpiSceneFaults, InputThatOneRankCannotLoad) {
  VOXLINK_REQUIRE_DATA("mesh/bunny_npm.obj");
  TempDir dir, out;
  writeText(dir.file("bad.obj"), "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
  writeText(dir.file("good.scene.json"), R"({"grid": {"resolution": 64}, "objects": [
      {"type": "mesh", "file": ")" + dataPath("mesh/bunny_npm.obj") +
                                             R"("}]})");
  writeText(dir.file("bad.scene.json"), R"({"grid": {"resolution": 64}, "objects": [
      {"type": "mesh", "file": ")" + dir.file("bad.obj") +
                                            R"("}]})");
  const std::string tail = " -q -o " + out.file("s.vxl");
  const Launch r = runLauncher("-n 1 VOXLINK scene build " + dir.file("good.scene.json") + tail +
                               " : -n 1 VOXLINK scene build " + dir.file("bad.scene.json") + tail +
                               " : -n 1 VOXLINK scene build " + dir.file("good.scene.json") + tail);
  EXPECT_NE(r.status, 0);
  expectOneLineFromRank(r, 1, "bad.obj");
  EXPECT_TRUE(listDir(out.path()).empty());
}

// Rank 2 of 3 loads another mesh than rank 0: its voxels would not belong to the same scene.
TEST(MpiSceneFaults, InputsThatDifferOnOneRank) {
  VOXLINK_REQUIRE_DATA("mesh/c3dtm_stanford-bunny.obj");
  TempDir dir, out;
  for (const char* mesh : {"bunny_npm", "c3dtm_stanford-bunny"})
    writeText(dir.file(std::string(mesh) + ".scene.json"),
              R"({"grid": {"resolution": 64}, "objects": [{"type": "mesh", "file": ")" +
                  dataPath(std::string("mesh/") + mesh + ".obj") + R"("}]})");
  const std::string tail = " -q -o " + out.file("s.vxl");
  const std::string small = "VOXLINK scene build " + dir.file("bunny_npm.scene.json") + tail;
  const Launch r = runLauncher("-n 2 " + small + " : -n 1 VOXLINK scene build " +
                               dir.file("c3dtm_stanford-bunny.scene.json") + tail);
  EXPECT_EQ(r.status, 2) << r.err;
  expectOneLineFromRank(r, 2, "differ from rank 0's");
  EXPECT_TRUE(listDir(out.path()).empty());
}

// Rank 0, which writes the merged file, may not write past 64 KiB (RLIMIT_FSIZE, as a full
// disk); TCP between the ranks, as in MpiFaults.DiskFullOnOneRank.
TEST(MpiSceneFaults, OutputThatRankZeroCannotWrite) {
  VOXLINK_REQUIRE_DATA("mesh/c3dtm_stanford-bunny.obj");
  TempDir dir, out;
  writeText(dir.file("s.scene.json"), R"({"grid": {"resolution": 256}, "objects": [
      {"type": "mesh", "file": ")" + dataPath("mesh/c3dtm_stanford-bunny.obj") +
                                          R"("}]})");
  const std::string args =
      "scene build " + dir.file("s.scene.json") + " -q -o " + out.file("s.vxl");
  const Launch r = runLauncher(
      "--mca btl self,tcp -n 1 sh -c \"trap '' XFSZ; ulimit -f 128; exec "
      "\\$0 " +
      args + "\" VOXLINK : -n 2 VOXLINK " + args);
  EXPECT_EQ(r.status, 3) << r.err;
  expectOneLineFromRank(r, 0, "File too large");
  EXPECT_TRUE(listDir(out.path()).empty());
}

// A missing output folder: every rank sees it before any work, rank 0 says it once.
TEST(MpiSceneFaults, OutputFolderMissing) {
  VOXLINK_REQUIRE_DATA("mesh/bunny_npm.obj");
  TempDir dir;
  writeText(dir.file("s.scene.json"), R"({"objects": [{"type": "mesh", "file": ")" +
                                          dataPath("mesh/bunny_npm.obj") + R"("}]})");
  const Launch r = runRanks(
      2, {"scene", "build", dir.file("s.scene.json"), "-q", "-o", dir.file("no/such/s.vxl")});
  EXPECT_NE(r.status, 0);
  expectOneLineFromRank(r, 0, "no/such");
}

TEST(MpiSceneFaults, GlVoxelizerRefusesSeveralRanks) {
  VOXLINK_REQUIRE_DATA("mesh/bunny_npm.obj");
  TempDir dir;
  writeText(dir.file("s.scene.json"), R"({"objects": [{"type": "mesh", "file": ")" +
                                          dataPath("mesh/bunny_npm.obj") + R"("}]})");
  const Launch r = runRanks(2, {"scene", "build", dir.file("s.scene.json"), "--voxelizer", "gl",
                                "-q", "-o", dir.file("s.vxl")});
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("--voxelizer gl runs in one process"), std::string::npos) << r.err;
  EXPECT_TRUE(listDir(dir.path()).size() == 1u);
}

}  // namespace
}  // namespace voxlink::testing
