// SPDX-License-Identifier: BSD-3-Clause
// A rank SIGKILLed while it works, under mpirun, for every command that runs on several ranks
// (docs/scale.md, "Faults"): convert, krige, grf and scene build, with rank 1 and with rank 0
// (which created the temporaries) as the victim. Every rank ends, mpirun's one line names the
// rank and the signal, the exit status is non-zero and no output or temporary is left.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include "tests/mpi/killed_rank.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

enum class Job { kConvert, kKrige, kGrf, kSceneBuild };

struct KillCase {
  const char* name;
  Job job;
  int victim;
  // >= 0: killed this long after the output's temporary appears; -1: once the victim has
  // spent kSceneKillCpuMs of CPU (a scene build creates its file only at its end).
  int delayMs;
};

constexpr int kSceneKillCpuMs = 300;

// Test names and failure messages show the case's name, not its bytes.
void PrintTo(const KillCase& c, std::ostream* os) { *os << c.name; }

std::vector<uint8_t> noise(size_t bytes) {
  std::vector<uint8_t> v(bytes);
  uint32_t x = 99;
  for (uint8_t& b : v) b = static_cast<uint8_t>((x = x * 1664525u + 1013904223u) >> 24);
  return v;
}

// 2,000 scattered 3-D samples of a smooth field with noise in a 64^3 box.
void writeSamples(const std::string& path) {
  std::ofstream out(path);
  out << "X,Y,Z,V\n";
  uint32_t x = 4242;
  auto uniform = [&x] { return (x = x * 1664525u + 1013904223u) / 4294967296.0; };
  for (int i = 0; i < 2000; ++i) {
    const double px = 64 * uniform(), py = 64 * uniform(), pz = 64 * uniform();
    out << px << "," << py << "," << pz << "," << px + 0.5 * py + 0.1 * pz + uniform() << "\n";
  }
}

// The job's inputs, written into `in`, and its arguments. Each is large enough that no rank is
// done when the kill point comes on a quiet machine (one process, one thread, here: convert
// about 1.6 s, krige 1.6 s of CPU, grf 1.2 s, scene build about 1.5 s).
std::string prepare(Job job, TempDir& in, const std::string& outDir) {
  const std::string out = outDir + "/";
  switch (job) {
    case Job::kConvert:
      writeBytes(in.file("n.raw"), noise(512 * 512 * 512));
      return "convert " + in.file("n.raw") +
             " --dims 512,512,512 --type u8 --keep-all --threads 1 -q -o " + out + "n.vxl";
    case Job::kKrige:
      writeSamples(in.file("s.csv"));
      return "krige " + in.file("s.csv") +
             " --value V --z Z --dims 80,80,80 --origin 0,0,0 --spacing 1,1,1 -k 16 "
             "--variogram exp:psill=1,range=20 --threads 1 -q -o " +
             out + "k.nhdr";
    case Job::kGrf:
      return "grf --dims 256,256,192 --variogram exp:range=4 --fft-size 32 --type f32 "
             "--threads 1 -q -o " +
             out + "f.npy";
    case Job::kSceneBuild:
      std::ofstream(in.file("s.json"))
          << R"({"grid": {"resolution": 1200}, "objects": [{"type": "mesh", "file": ")"
          << dataPath("mesh/c3dtm_stanford-bunny.obj") << "\"}]}";
      return "scene build " + in.file("s.json") + " -q -o " + out + "s.vxl";
  }
  return {};
}

class KilledRank : public ::testing::TestWithParam<KillCase> {};

TEST_P(KilledRank, LeavesNothing) {
  const KillCase& c = GetParam();
  if (c.job == Job::kSceneBuild) VOXLINK_REQUIRE_DATA("mesh/c3dtm_stanford-bunny.obj");
  TempDir in, out;
  const std::string args = prepare(c.job, in, out.path());
  const KillPoint when =
      c.delayMs >= 0 ? onceFolderHoldsFile(out.path(), c.delayMs) : onceCpuSpent(kSceneKillCpuMs);
  expectKilledRankLeavesNothing(3, c.victim, args, out.path(), when);
}

INSTANTIATE_TEST_SUITE_P(
    MpiFaults, KilledRank,
    ::testing::Values(
        // Rank 1 inside the encoding; rank 1 at once, while rank 0 waits inside MPI right after
        // creating the temporary (Open MPI ends rank 0 with _exit(): no handler runs, its
        // helper removes the file); rank 0, which created the temporary, itself.
        KillCase{"ConvertRank1", Job::kConvert, 1, 100},
        KillCase{"ConvertRank1WhileRankZeroWaitsInMpi", Job::kConvert, 1, 0},
        KillCase{"ConvertRank0", Job::kConvert, 0, 100},
        // The same points for the grids rank 0 creates and every rank writes.
        KillCase{"KrigeRank1", Job::kKrige, 1, 100},
        KillCase{"KrigeRank1WhileRankZeroWaitsInMpi", Job::kKrige, 1, 0},
        KillCase{"KrigeRank0", Job::kKrige, 0, 100}, KillCase{"GrfRank1", Job::kGrf, 1, 100},
        KillCase{"GrfRank1WhileRankZeroWaitsInMpi", Job::kGrf, 1, 0},
        KillCase{"GrfRank0", Job::kGrf, 0, 100},
        // Voxelizing its brick layers (no file exists yet).
        KillCase{"SceneBuildRank1", Job::kSceneBuild, 1, -1},
        KillCase{"SceneBuildRank0", Job::kSceneBuild, 0, -1}),
    [](const ::testing::TestParamInfo<KillCase>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace voxlink::testing
