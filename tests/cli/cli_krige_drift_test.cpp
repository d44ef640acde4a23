// SPDX-License-Identifier: BSD-3-Clause
// `voxlink krige --drift` and `--external-drift COLUMN --external-drift-grid FILE` as a user
// runs them: a trend inside the drift's span is reproduced exactly at every node (also beyond
// the samples), and bad drift input fails in one line with nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

#include "sources/volume_source.h"
#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

constexpr uint32_t kNx = 12, kNy = 9;

double nodeDrift(uint32_t i, uint32_t j) { return 0.7 * i - 0.2 * j + (i * j) % 5; }

// The drift at every node of the kNx x kNy grid as NAME.nhdr + NAME.raw (f64).
std::string writeDriftGrid(TempDir& dir, const std::string& name, bool withNaN = false) {
  std::vector<uint8_t> bytes(kNx * kNy * sizeof(double));
  for (uint32_t j = 0; j < kNy; ++j)
    for (uint32_t i = 0; i < kNx; ++i) {
      const double v = withNaN && i == 3 && j == 2 ? NAN : nodeDrift(i, j);
      std::memcpy(&bytes[(j * kNx + i) * sizeof(double)], &v, sizeof v);
    }
  writeBytes(dir.file(name + ".raw"), bytes);
  std::ofstream(dir.file(name + ".nhdr"))
      << "NRRD0004\ntype: double\ndimension: 3\nsizes: " << kNx << " " << kNy
      << " 1\nencoding: raw\nendian: little\ndata file: " << name << ".raw\n";
  return dir.file(name + ".nhdr");
}

// Samples at scattered points with u = the node formula's value at them (a smooth field
// elsewhere) and v = 2 u + 5 + 3 x - y: inside the span of {1, u, x, y}.
std::string writeSamples(TempDir& dir) {
  std::ofstream csv(dir.file("s.csv"));
  csv.precision(17);  // every digit: v must stay in the drift's span
  csv << "x,y,u,v\n";
  for (int k = 0; k < 40; ++k) {
    // Scattered, not on a few lines (which would make local drifts degenerate).
    const double x = (k * 7919 % 101) / 101.0 * 11, y = (k * 104729 % 89) / 89.0 * 8;
    const double u = std::sin(0.9 * x) + 0.3 * y * y;
    csv << x << "," << y << "," << u << "," << 2 * u + 5 + 3 * x - y << "\n";
  }
  return dir.file("s.csv");
}

std::vector<double> readGrid(const std::string& path) {
  auto source = sources::openVolume(path);
  EXPECT_TRUE(source) << source.message();
  auto bytes = sources::readAll(**source);
  std::vector<double> out(bytes->size() / sizeof(double));
  std::memcpy(out.data(), bytes->data(), bytes->size());
  return out;
}

std::vector<std::string> krige(TempDir& dir, const std::vector<std::string>& extra,
                               const std::string& dims = "12,9") {
  std::vector<std::string> args = {"krige",       writeSamples(dir),
                                   "--value",     "v",
                                   "--variogram", "exp:nugget=0,psill=1,range=6",
                                   "--dims",      dims,
                                   "--origin",    "-3,-2",
                                   "--spacing",   "1.5,1.5"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

TEST(CliKrigeDrift, ATrendInTheDriftsSpanIsReproducedAtEveryNode) {
  TempDir dir;
  const std::string drift = writeDriftGrid(dir, "u");
  for (const std::string k : {"0", "10"}) {
    auto r = runVoxlink(
        krige(dir, {"--drift", "linear", "--external-drift", "u", "--external-drift-grid", drift,
                    "-k", k, "-o", dir.file("k" + k + ".npy")}));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("drift: linear + external 'u' (4 terms"), std::string::npos) << r.out;
    const std::vector<double> got = readGrid(dir.file("k" + k + ".npy"));
    ASSERT_EQ(got.size(), size_t{kNx} * kNy);
    double worst = 0;
    for (uint32_t j = 0; j < kNy; ++j)
      for (uint32_t i = 0; i < kNx; ++i) {
        const double x = -3 + 1.5 * i, y = -2 + 1.5 * j;
        worst =
            std::max(worst, std::fabs(got[j * kNx + i] - (2 * nodeDrift(i, j) + 5 + 3 * x - y)));
      }
    EXPECT_LT(worst, 1e-8) << "-k " << k;
  }
  // Ordinary kriging cannot follow the trend beyond the samples: the check above can fail.
  auto r = runVoxlink(krige(dir, {"-o", dir.file("ok.npy")}));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<double> ok = readGrid(dir.file("ok.npy"));
  EXPECT_GT(std::fabs(ok[0] - (2 * nodeDrift(0, 0) + 5 - 9 + 2)), 0.5);
}

TEST(CliKrigeDrift, BadDriftInputFailsInOneLineAndWritesNothing) {
  TempDir dir;
  const std::string drift = writeDriftGrid(dir, "u");
  const std::string bad = writeDriftGrid(dir, "bad", true);
  auto expectOneLine = [&](const std::vector<std::string>& extra,
                           const std::vector<std::string>& mentions,
                           const std::string& dims = "12,9") {
    auto r = runVoxlink(krige(dir, extra, dims));
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    for (const std::string& m : mentions) EXPECT_NE(r.err.find(m), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("k.npy"))) << r.err;
  };
  expectOneLine({"--external-drift", "u", "-o", dir.file("k.npy")}, {"--external-drift-grid"});
  expectOneLine({"--external-drift", "w", "--external-drift-grid", drift, "-o", dir.file("k.npy")},
                {"s.csv", "external drift column 'w' not found"});
  expectOneLine({"--external-drift", "u", "--external-drift-grid", drift, "-o", dir.file("k.npy")},
                {"u.nhdr", "12 x 9 x 1", "12 x 8 x 1"}, "12,8");
  expectOneLine({"--external-drift", "u", "--external-drift-grid", bad, "-o", dir.file("k.npy")},
                {"bad.nhdr", "x 3, y 2", "not finite"});
  expectOneLine({"--drift", "quadratic", "--kind", "sk", "--mean", "0", "-o", dir.file("k.npy")},
                {"--kind ok"});
  expectOneLine({"--drift", "cubic", "-o", dir.file("k.npy")}, {"--drift"});
}

}  // namespace
}  // namespace voxlink::testing
