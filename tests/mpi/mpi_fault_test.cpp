// SPDX-License-Identifier: BSD-3-Clause
// One rank failing under mpirun (docs/scale.md): a bad value in its slab, a slab it cannot read,
// a full disk (a file size limit on that rank). Every rank ends, the exit status is non-zero,
// stderr names the rank and the cause, and the output folder stays empty: no output, no
// temporary. A killed rank: mpi_killed_rank_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "tests/mpi/mpi_launch.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

std::vector<uint8_t> noise(size_t bytes) {
  std::vector<uint8_t> v(bytes);
  uint32_t x = 99;
  for (uint8_t& b : v) b = static_cast<uint8_t>((x = x * 1664525u + 1013904223u) >> 24);
  return v;
}

// 37x29x53 f32 with one NaN at z = 50: brick layer 6 of 7, which rank 2 of 3 converts.
TEST(MpiFaults, BadValueOnOneRank) {
  TempDir in, out;
  std::vector<float> values(37 * 29 * 53, 1.0f);
  values[(50 * 29 + 3) * 37 + 4] = NAN;
  std::vector<uint8_t> bytes(values.size() * 4);
  std::memcpy(bytes.data(), values.data(), bytes.size());
  writeBytes(in.file("v.raw"), bytes);
  const Launch r = runRanks(3, {"convert", in.file("v.raw"), "--dims", "37,29,53", "--type", "f32",
                                "--threshold", "0.5", "-q", "-o", out.file("v.vxl")});
  EXPECT_EQ(r.status, 1) << r.err;
  expectOneLineFromRank(r, 2, "(4, 3, 50) is not finite");
  EXPECT_TRUE(listDir(out.path()).empty());
}

// A detached NRRD with one gzip file per slice; the slice rank 1 of 2 reads is corrupt (what
// a reader cannot know before it decompresses it).
TEST(MpiFaults, UnreadableSlabOnOneRank) {
  TempDir in, out;
  for (int z = 0; z < 32; ++z) {
    const std::string name = in.file(std::string("s") + std::to_string(z) + ".raw");
    writeBytes(name, noise(24 * 24));
    ASSERT_EQ(std::system(("gzip -n " + name).c_str()), 0);
  }
  writeBytes(in.file("s27.raw.gz"), noise(100));
  std::ofstream(in.file("v.nhdr")) << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 24 24 32\n"
                                      "encoding: gzip\ndata file: s%d.raw.gz 0 31 1\n";
  const Launch r = runRanks(
      2, {"convert", in.file("v.nhdr"), "--threshold", "100", "-q", "-o", out.file("v.vxl")});
  EXPECT_NE(r.status, 0);
  expectOneLineFromRank(r, 1, "s27.raw.gz");
  EXPECT_TRUE(listDir(out.path()).empty());
}

// Rank 1 of 3 may not write past 1 MiB (RLIMIT_FSIZE, SIGXFSZ ignored: EFBIG, as a full disk
// gives ENOSPC) into a 3.5 MB output. TCP between the ranks: the limit would also stop Open
// MPI's shared-memory transport from sizing its segment.
TEST(MpiFaults, DiskFullOnOneRank) {
  TempDir in, out;
  writeBytes(in.file("n.raw"), noise(96 * 96 * 96));
  const std::string args = "convert " + in.file("n.raw") +
                           " --dims 96,96,96 --type u8 --keep-all -q -o " + out.file("n.vxl");
  const Launch r = runLauncher("--mca btl self,tcp -n 1 VOXLINK " + args +
                               " : -n 1 sh -c \"trap '' XFSZ; ulimit -f 2048; exec \\$0 " + args +
                               "\" VOXLINK : -n 1 VOXLINK " + args);
  EXPECT_EQ(r.status, 3) << r.err;
  expectOneLineFromRank(r, 1, "write failed: File too large");
  EXPECT_TRUE(listDir(out.path()).empty());
}

}  // namespace
}  // namespace voxlink::testing
