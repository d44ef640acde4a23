// SPDX-License-Identifier: BSD-3-Clause
// --threads 1 runs every command that takes it on one thread, and --threads 2 gives the same bytes.
// The count comes from the parallel facility itself (base/parallel_for.h): with
// VOXLINK_THREAD_CENSUS set it writes each thread that does its work to that file once, so the
// test sees the real dispatch path, not a thread list that MPI or a plugin may add idle threads to.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

constexpr const char* kFoot = "ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd";
constexpr const char* kWalker = "geostat/gstat_csv/walker.csv";

struct CensusRun {
  CommandResult result;
  size_t threads = 0;  // distinct threads that did the facility's work
};

// Runs `voxlink args... --threads N` with the census on; `output` is the file it writes.
CensusRun runCounted(TempDir& dir, std::vector<std::string> args, unsigned threads) {
  const std::string census = dir.file("census-" + std::to_string(threads));
  std::filesystem::remove(census);
  args.insert(args.end(), {"--threads", std::to_string(threads), "-q"});
  setenv("VOXLINK_THREAD_CENSUS", census.c_str(), 1);
  CensusRun run{runVoxlink(args)};
  unsetenv("VOXLINK_THREAD_CENSUS");
  std::ifstream in(census);
  std::set<std::string> ids;
  for (std::string line; std::getline(in, line);) ids.insert(line);
  run.threads = ids.size();
  return run;
}

// One command at --threads 1 and 2: one thread at 1, and the same bytes from both. Returns the
// threads the census saw at 2.
size_t expectOneThreadAndSameBytes(TempDir& dir, const std::vector<std::string>& argsBeforeOutput,
                                   const std::string& extension) {
  std::vector<std::string> outputs;
  size_t atTwo = 0;
  for (unsigned threads : {1u, 2u}) {
    const std::string out = dir.file("out" + std::to_string(threads) + extension);
    std::vector<std::string> args = argsBeforeOutput;
    args.insert(args.end(), {"-o", out});
    const CensusRun run = runCounted(dir, args, threads);
    EXPECT_EQ(run.result.status, 0) << argsBeforeOutput[0] << ": " << run.result.err;
    if (threads == 1) {
      EXPECT_EQ(run.threads, 1u) << argsBeforeOutput[0] << " --threads 1";
    } else {
      atTwo = run.threads;
    }
    outputs.push_back(out);
  }
  EXPECT_EQ(readBytes(outputs[0]), readBytes(outputs[1])) << argsBeforeOutput[0];
  return atTwo;
}

TEST(CliThreads, ConvertRunsOnOneThreadWithThreadsOne) {
  VOXLINK_REQUIRE_DATA(kFoot);
  TempDir dir;
  // The census can see more than one thread: a helper that the scheduler runs late may find no
  // work left in one loop, but not in all 8 loops of this conversion.
  EXPECT_GE(
      expectOneThreadAndSameBytes(dir, {"convert", dataPath(kFoot), "--threshold", "60"}, ".vxl"),
      2u);
}

TEST(CliThreads, PackRunsOnOneThreadWithThreadsOne) {
  VOXLINK_REQUIRE_DATA(kFoot);
  TempDir dir;
  const std::string vxl = dir.file("foot.vxl");
  const auto r = runVoxlink({"convert", dataPath(kFoot), "--threshold", "60", "-o", vxl, "-q"});
  ASSERT_EQ(r.status, 0) << r.err;
  expectOneThreadAndSameBytes(dir, {"pack", vxl}, ".vxl");
}

TEST(CliThreads, KrigeRunsOnOneThreadWithThreadsOne) {
  VOXLINK_REQUIRE_DATA(kWalker);
  TempDir dir;
  expectOneThreadAndSameBytes(dir,
                              {"krige", dataPath(kWalker), "--value", "V", "--variogram",
                               "sph:nugget=22144,psill=70207.9,range=35.085", "-k", "16", "--dims",
                               "130,150", "--origin", "1,1", "--spacing", "2,2"},
                              ".npy");
}

TEST(CliThreads, GlobalKrigeRunsOnOneThreadWithThreadsOne) {
  VOXLINK_REQUIRE_DATA(kWalker);
  TempDir dir;
  // The same bytes: below 2048 samples OpenBLAS factorizes on one thread whatever --threads
  // says (its threaded Cholesky rounds differently). Spherical takes the compact-support path,
  // exponential the dense one.
  for (const char* model : {"sph:nugget=22144,psill=70207.9,range=35.085",
                            "exp:nugget=22144,psill=70207.9,range=35.085"})
    expectOneThreadAndSameBytes(dir,
                                {"krige", dataPath(kWalker), "--value", "V", "--variogram", model,
                                 "--dims", "65,75", "--origin", "1,1", "--spacing", "4,4"},
                                ".npy");
}

TEST(CliThreads, GrfRunsOnOneThreadWithThreadsOne) {
  TempDir dir;
  expectOneThreadAndSameBytes(dir, {"grf", "--dims", "64,64,64", "--seed", "7"}, ".npy");
}

// The commands that gained --threads with the GL move's pass over the CLI: scene builds (every
// surface mode), unpack, export and the exact tracer (Embree's TBB bounded through the limit).
TEST(CliThreads, SceneBuildRunsOnOneThreadWithThreadsOne) {
  TempDir dir;
  const std::string house = std::string(VOXLINK_SAMPLES_DIR) + "/scenes/house.scene.json";
  for (const char* surface : {"mean", "planes", "triangles"})
    expectOneThreadAndSameBytes(
        dir, {"scene", "build", house, "--resolution", "96", "--surface", surface}, ".vxl");
}

TEST(CliThreads, UnpackAndExportRunOnOneThreadWithThreadsOne) {
  VOXLINK_REQUIRE_DATA(kFoot);
  TempDir dir;
  const std::string vxl = dir.file("foot.vxl"), packed = dir.file("foot.packed.vxl");
  ASSERT_EQ(runVoxlink({"convert", dataPath(kFoot), "--threshold", "60", "-o", vxl, "-q"}).status,
            0);
  ASSERT_EQ(runVoxlink({"pack", vxl, "-o", packed, "-q"}).status, 0);
  expectOneThreadAndSameBytes(dir, {"unpack", packed}, ".vxl");
  expectOneThreadAndSameBytes(dir, {"export", vxl}, ".nrrd");
}

TEST(CliThreads, RenderExactRunsOnOneThreadWithThreadsOne) {
  TempDir dir;
  const std::string house = std::string(VOXLINK_SAMPLES_DIR) + "/scenes/house.scene.json";
  expectOneThreadAndSameBytes(dir, {"render-exact", house, "--size", "48x48", "--effects", "all"},
                              ".png");
}

}  // namespace
}  // namespace voxlink::testing
