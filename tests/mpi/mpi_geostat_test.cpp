// SPDX-License-Identifier: BSD-3-Clause
// `mpirun -n N voxlink krige|grf ...` (docs/scale.md): the grids N ranks write together are
// byte for byte the grids one process writes, for 1 to 4 ranks: local and global kriging, 2-D
// and 3-D, with a drift, grid sizes that do not divide among the ranks, ranks with no block;
// random fields (the same field for the same seed). And one rank failing leaves nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "tests/mpi/mpi_launch.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

// `count` scattered samples of a smooth field with noise, in a 40 x 30 (x 20 in 3-D) box.
void writeSamples(const std::string& path, int dimension, int count) {
  std::ofstream out(path);
  out << (dimension == 3 ? "X,Y,Z,V\n" : "X,Y,V\n");
  uint32_t noise = 777;
  auto uniform = [&noise] { return (noise = noise * 1664525u + 1013904223u) / 4294967296.0; };
  for (int i = 0; i < count; ++i) {
    const double x = 40 * uniform(), y = 30 * uniform(), z = dimension == 3 ? 20 * uniform() : 0;
    const double v = std::sin(x * 0.2) + std::cos(y * 0.15) + 0.1 * z + 0.3 * uniform();
    out << x << "," << y << ",";
    if (dimension == 3) out << z << ",";
    out << v << "\n";
  }
}

struct Case {
  const char* name;
  const char* command;  // krige or grf
  int dimension;        // of the samples (krige)
  std::vector<std::string> options;
  std::vector<std::string> files;  // what the command writes, named in `options` as OUT/...
};

const std::vector<Case>& cases() {
  static const std::vector<Case> all = {
      {"local_2d",
       "krige",
       2,
       {"--dims", "53,47", "-k", "12", "--variogram", "sph:nugget=0.05,psill=1,range=15", "-o",
        "OUT/k.nhdr"},
       {"k.nhdr", "k.raw", "k_variance.nhdr", "k_variance.raw"}},
      {"local_3d_linear_drift_f32",
       "krige",
       3,
       {"--z", "Z", "--dims", "23,19,21", "-k", "10", "--drift", "linear", "--variogram",
        "exp:psill=1,range=12", "--type", "f32", "-o", "OUT/k.npy"},
       {"k.npy", "k_variance.npy"}},
      {"global_2d_quadratic_drift",
       "krige",
       2,
       {"--dims", "41,37", "-k", "0", "--drift", "quadratic", "--variogram",
        "gau:nugget=0.01,psill=1,range=20", "-o", "OUT/k.nhdr"},
       {"k.nhdr", "k.raw", "k_variance.nhdr", "k_variance.raw"}},
      {"global_3d",
       "krige",
       3,
       {"--z", "Z", "--dims", "17,13,11", "-k", "0", "--variogram", "exp:psill=1,range=12", "-o",
        "OUT/k.npy"},
       {"k.npy", "k_variance.npy"}},
      // One slab of two brick rows (local) and one block of nodes (global): ranks with none.
      {"local_3d_tiny",
       "krige",
       3,
       {"--z", "Z", "--dims", "20,20,8", "-k", "8", "--variogram", "sph:psill=1,range=15", "-o",
        "OUT/k.npy"},
       {"k.npy", "k_variance.npy"}},
      {"global_2d_tiny",
       "krige",
       2,
       {"--dims", "10,10", "-k", "0", "--variogram", "sph:psill=1,range=15", "-o", "OUT/k.npy"},
       {"k.npy", "k_variance.npy"}},
      {"grf_3d",
       "grf",
       0,
       {"--dims", "40,35,27", "--variogram", "exp:range=6", "--seed", "7", "--fft-size", "48",
        "--type", "f32", "-o", "OUT/f.npy"},
       {"f.npy"}},
      {"grf_2d",
       "grf",
       0,
       {"--dims", "150,101,1", "--variogram", "sph:range=9", "--fft-size", "48", "-o",
        "OUT/f.nhdr"},
       {"f.nhdr", "f.raw"}},
      {"grf_tiny", "grf", 0, {"--dims", "8,8,8", "-o", "OUT/f.npy"}, {"f.npy"}},
  };
  return all;
}

std::vector<std::string> argsFor(const Case& c, const std::string& samples,
                                 const std::string& outDir) {
  std::vector<std::string> args{c.command};
  if (c.dimension > 0) args.insert(args.end(), {samples, "--value", "V"});
  for (std::string o : c.options) {
    if (o.rfind("OUT/", 0) == 0) o = outDir + "/" + o.substr(4);
    args.push_back(o);
  }
  return args;
}

class SameGrids : public ::testing::TestWithParam<std::tuple<size_t, int>> {};

TEST_P(SameGrids, AsOneProcess) {
  const Case& c = cases()[std::get<0>(GetParam())];
  const int ranks = std::get<1>(GetParam());
  TempDir in, one, split;
  const std::string samples = in.file("s.csv");
  if (c.dimension > 0) writeSamples(samples, c.dimension, c.dimension == 3 ? 300 : 120);
  const Launch plain = runPlain(argsFor(c, samples, one.path()));
  ASSERT_EQ(plain.status, 0) << plain.err;
  const Launch r = runRanks(ranks, argsFor(c, samples, split.path()));
  ASSERT_EQ(r.status, 0) << r.err;
  for (const std::string& file : c.files) {
    const std::vector<uint8_t> expected = readBytes(one.file(file));
    ASSERT_FALSE(expected.empty()) << file;
    EXPECT_TRUE(readBytes(split.file(file)) == expected)
        << file << " differs on " << ranks << " ranks";
  }
  EXPECT_EQ(listDir(split.path()).size(), c.files.size());  // no temporary left
  // Only rank 0 prints the report: one "wrote:" line.
  EXPECT_EQ(r.out.find("wrote:"), r.out.rfind("wrote:")) << r.out;
}

std::string caseName(const ::testing::TestParamInfo<std::tuple<size_t, int>>& info) {
  return std::string(cases()[std::get<0>(info.param)].name) + "_ranks" +
         std::to_string(std::get<1>(info.param));
}

INSTANTIATE_TEST_SUITE_P(MpiGeostat, SameGrids,
                         ::testing::Combine(::testing::Range(size_t{0}, cases().size()),
                                            ::testing::Values(1, 2, 3, 4)),
                         caseName);

// A value that is not a number in the samples: rank 0 reads them, every rank stops.
TEST(MpiGeostatFaults, BadSampleValue) {
  TempDir in, out;
  std::ofstream(in.file("s.csv")) << "X,Y,V\n1,2,3\n4,5,abc\n7,1,2\n";
  const Launch r = runRanks(3, {"krige", in.file("s.csv"), "--value", "V", "--dims", "20,20",
                                "--variogram", "exp:psill=1,range=5", "-o", out.file("k.nhdr")});
  EXPECT_EQ(r.status, 2) << r.err;
  expectOneLineFromRank(r, 0, "line 3: column 'V': 'abc' is not a number");
  EXPECT_TRUE(listDir(out.path()).empty());
}

// Samples on a lattice up to z = 20, --max-distance 3.5: the nodes from z = 24 on have none in
// reach and would be NaN (the default --nodata), which the grid refuses. Of 3 ranks on a
// 20 x 20 x 40 grid (5 slabs of 8 x 2 brick rows), only rank 2 (slabs 3 and 4) has such nodes.
TEST(MpiGeostatFaults, NonFiniteNodesOnOneRank) {
  TempDir in, out;
  {
    std::ofstream s(in.file("s.csv"));
    s << "X,Y,Z,V\n";
    for (int z = 0; z <= 20; z += 2)
      for (int y = 0; y < 20; y += 2)
        for (int x = 0; x < 20; x += 2) s << x << "," << y << "," << z << "," << x + y + z << "\n";
  }
  const Launch r = runRanks(3, {"krige",
                                in.file("s.csv"),
                                "--value",
                                "V",
                                "--z",
                                "Z",
                                "--dims",
                                "20,20,40",
                                "--origin",
                                "0,0,0",
                                "--spacing",
                                "1,1,1",
                                "-k",
                                "8",
                                "--max-distance",
                                "3.5",
                                "--variogram",
                                "exp:psill=1,range=8",
                                "-o",
                                out.file("k.nhdr")});
  EXPECT_EQ(r.status, 2) << r.err;
  expectOneLineFromRank(r, 2, "value nan at node (0, 0, 24) is not finite");
  EXPECT_TRUE(listDir(out.path()).empty());
}

// The output folder is a regular file: rank 0 cannot create the temporaries.
TEST(MpiGeostatFaults, UnwritableOutputFolder) {
  TempDir dir;
  writeBytes(dir.file("notadir"), {1});
  const Launch r =
      runRanks(2, {"grf", "--dims", "16,16,16", "-o", dir.file("notadir") + "/f.nhdr"});
  EXPECT_NE(r.status, 0);
  expectOneLineFromRank(r, 0, "Not a directory");
  EXPECT_EQ(listDir(dir.path()), (std::vector<std::string>{"notadir"}));
}

// Rank 1 of 3 may not write past 64 KiB (RLIMIT_FSIZE, SIGXFSZ ignored: EFBIG, as a full disk
// gives ENOSPC) into a 1 MB field.
TEST(MpiGeostatFaults, DiskFullOnOneRank) {
  TempDir out;
  const std::string args =
      "grf --dims 64,64,32 --variogram exp:range=4 --fft-size 32 -q -o " + out.file("f.npy");
  const Launch r = runLauncher("--mca btl self,tcp -n 1 VOXLINK " + args +
                               " : -n 1 sh -c \"trap '' XFSZ; ulimit -f 128; exec \\$0 " + args +
                               "\" VOXLINK : -n 1 VOXLINK " + args);
  EXPECT_EQ(r.status, 3) << r.err;
  expectOneLineFromRank(r, 1, "write failed: File too large");
  EXPECT_TRUE(listDir(out.path()).empty());
}

TEST(MpiGeostatFaults, GrfStatsRefusedOnSeveralRanks) {
  TempDir out;
  const Launch r = runRanks(2, {"grf", "--dims", "16,16,16", "--stats", "-o", out.file("f.npy")});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("--stats runs in one process"), std::string::npos) << r.err;
  EXPECT_TRUE(listDir(out.path()).empty());
}

}  // namespace
}  // namespace voxlink::testing
