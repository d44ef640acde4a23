// SPDX-License-Identifier: BSD-3-Clause
// Memory that follows what a file stores, not its grid (issue 30): a valid file holding one
// voxel in a 65536 x 32768 x 1 grid of 4-voxel bricks took 72 s and 14.3 GB to render 64x64
// (brick tables over all 134 million bricks) and a dense export of a one-slice volume allocated
// a whole 4-slice brick layer. Each runs here under an address-space limit far below what the
// old code needed; a file whose occupied bricks span the grid is refused up front in one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <vector>

#include "format/bricked_volume.h"
#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

// A u8 volume of `dims` with 4-voxel bricks holding the given voxels (value 200), written to
// `path`.
void writeSparseFile(const std::string& path, std::array<uint32_t, 3> dims,
                     const std::vector<std::array<uint32_t, 3>>& voxels) {
  format::VolumeDescription d;
  d.dims = dims;
  d.brickSize = 4;
  d.valueType = StoredType::kU8;
  d.sourceType = ScalarType::kU8;
  format::BrickedVolumeBuilder builder(d);
  for (const auto& v : voxels) builder.add(v[0], v[1], v[2], 200, 0);
  auto volume = builder.build();
  ASSERT_TRUE(volume) << volume.message();
  ASSERT_TRUE(format::writeBrickedVolume(path, *volume).isOk());
}

bool viewerBuilt() { return runVoxlink({"render", "--help"}).status == 0; }

TEST(CliRenderMemory, OneVoxelInAHugeGridRendersInLittleMemory) {
  if (!addressSpaceLimitsWork()) GTEST_SKIP() << "AddressSanitizer cannot run under ulimit -v";
  if (!viewerBuilt()) GTEST_SKIP() << "built without the viewer";
  TempDir dir;
  writeSparseFile(dir.file("one.vxl"), {65536, 32768, 1}, {{40001, 20002, 0}});
  RunOptions limited;
  limited.addressSpaceBytes = uint64_t{3} << 30;  // the grid-wide tables alone took 14 GB
  limited.timeoutSeconds = 120;
  for (const char* sampling : {"voxel", "trilinear"}) {
    SCOPED_TRACE(sampling);
    const auto r = runVoxlink({"render", dir.file("one.vxl"), "-o", dir.file("one.png"), "--size",
                               "64x64", "--sampling", sampling},
                              limited);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir.file("one.png")));
  }
}

// Two voxels at opposite corners: the occupied bricks' box is the whole grid, and its tables
// (8 bytes per brick, twice: built, then uploaded) cannot fit in 2 GiB. Refused before they
// are built, naming the file, the bytes needed and the bytes the process may use.
TEST(CliRenderMemory, TablesThatCannotFitAreRefusedUpFront) {
  if (!addressSpaceLimitsWork()) GTEST_SKIP() << "AddressSanitizer cannot run under ulimit -v";
  if (!viewerBuilt()) GTEST_SKIP() << "built without the viewer";
  TempDir dir;
  writeSparseFile(dir.file("corners.vxl"), {65536, 32768, 1}, {{0, 0, 0}, {65535, 32767, 0}});
  RunOptions limited;
  limited.addressSpaceBytes = uint64_t{2} << 30;
  limited.timeoutSeconds = 120;
  const auto r = runVoxlink(
      {"render", dir.file("corners.vxl"), "-o", dir.file("c.png"), "--size", "64x64"}, limited);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.find("voxlink: " + dir.file("corners.vxl") + ": rendering needs "), 0u) << r.err;
  EXPECT_NE(r.err.find("16384 x 8192 x 1 bricks around the occupied ones), more than the "
                       "2147483648 bytes this process may use"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"corners.vxl"});
}

// render --reference loads the dense source in float64: 16384 x 16384 u8 needs 2.4 GB with its
// bytes, refused under 2 GiB before it is read or a frame rendered, naming the source. (Under
// 1 GiB llvmpipe cannot start its threads.)
TEST(CliRenderMemory, ReferenceThatCannotFitIsRefusedUpFront) {
  if (!addressSpaceLimitsWork()) GTEST_SKIP() << "AddressSanitizer cannot run under ulimit -v";
  if (!viewerBuilt()) GTEST_SKIP() << "built without the viewer";
  TempDir dir;
  {
    std::ofstream raw(dir.file("slice.raw"), std::ios::binary);
    raw.seekp(6 * 16384 + 5);
    raw.put(char(200));
    raw.seekp(int64_t{16384} * 16384 - 1);
    raw.put(0);  // the rest is a hole: no disk blocks
  }
  auto r = runVoxlink({"convert", dir.file("slice.raw"), "--dims", "16384,16384,1", "--type", "u8",
                       "--threshold", "100", "--brick", "4", "-o", dir.file("slice.vxl"), "-q"});
  ASSERT_EQ(r.status, 0) << r.err;
  RunOptions limited;
  limited.addressSpaceBytes = uint64_t{2} << 30;
  limited.timeoutSeconds = 120;
  r = runVoxlink(
      {"render", dir.file("slice.vxl"), "-o", dir.file("s.png"), "--size", "32x32", "--reference"},
      limited);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(dir.file("slice.raw") +
                       ": the dense volume needs 2415919104 bytes (16384 x 16384 x 1 voxels as "
                       "u8 and float64), more than the 2147483648 bytes this process may use"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("s.png")));
}

// A one-slice volume exports with a one-slice layer: 16384 x 16384 u8 is 256 MiB a slice, and
// the 4-slice brick layer it took (1 GiB) does not fit in 768 MiB.
TEST(CliRenderMemory, OneSliceVolumeExportsWithAOneSliceLayer) {
  if (!addressSpaceLimitsWork()) GTEST_SKIP() << "AddressSanitizer cannot run under ulimit -v";
  TempDir dir;
  writeSparseFile(dir.file("slice.vxl"), {16384, 16384, 1}, {{5, 6, 0}});
  RunOptions limited;
  limited.addressSpaceBytes = uint64_t{768} << 20;
  limited.timeoutSeconds = 120;
  const auto r =
      runVoxlink({"export", dir.file("slice.vxl"), "-o", dir.file("slice.nhdr")}, limited);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(std::filesystem::file_size(dir.file("slice.raw")), uint64_t{16384} * 16384);
  const auto bytes = readBytes(dir.file("slice.raw"));
  EXPECT_EQ(bytes[6 * 16384 + 5], 200);
  EXPECT_EQ(std::count(bytes.begin(), bytes.end(), uint8_t{0}), int64_t{16384} * 16384 - 1);
}

}  // namespace
}  // namespace voxlink::testing
