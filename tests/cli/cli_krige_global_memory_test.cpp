// SPDX-License-Identifier: BSD-3-Clause
// Global kriging whose n x n matrix would not fit in what the process may use is refused before
// it starts, in one line naming the option that makes it fit, with nothing written (issue 27,
// item 5), for a model with compact support (which forms K^-1 in the factor's place) as for one
// without.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

TEST(CliKrigeGlobalMemory, AMatrixThatDoesNotFitIsRefusedNamingTheNeighboursOption) {
  if (!addressSpaceLimitsWork()) GTEST_SKIP() << "AddressSanitizer cannot run under ulimit -v";
  TempDir dir;
  const std::string csv = dir.file("s.csv");
  {
    std::ofstream out(csv);
    out << "x,y,v\n";
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0, 1000);
    for (int i = 0; i < 12000; ++i) out << u(rng) << "," << u(rng) << "," << u(rng) << "\n";
  }
  RunOptions limited;
  limited.addressSpaceBytes = uint64_t{768} << 20;  // the 12000 x 12000 matrix alone is 1.1 GB
  limited.timeoutSeconds = 60;
  for (const char* model : {"sph:nugget=1,psill=9,range=30", "exp:nugget=1,psill=9,range=30"}) {
    const std::string out = dir.file("k.npy");
    const CommandResult r =
        runVoxlink({"krige", csv, "--x", "x", "--y", "y", "--value", "v", "--variogram", model,
                    "-k", "0", "--dims", "20,20", "--threads", "2", "-o", out},
                   limited);
    EXPECT_NE(r.status, 0) << model;
    EXPECT_NE(r.err.find("global kriging of 12000 samples needs"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--neighbours"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << model;
    EXPECT_FALSE(std::filesystem::exists(dir.file("k_variance.npy"))) << model;
  }
}

}  // namespace
}  // namespace voxlink::testing
