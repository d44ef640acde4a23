// SPDX-License-Identifier: BSD-3-Clause
// voxlink export to dense NRRD: read back by the project's NRRD reader, the source's type and
// spacing kept, removed voxels = the fill, and converting the export again with the same
// threshold gives the same voxels and values; bad fills and paths leave no file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "format/bricked_volume.h"
#include "format/voxel_locator.h"
#include "format/voxlink_file.h"
#include "pack/open_file.h"
#include "sources/volume_source.h"
#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

struct Voxel {
  uint32_t x, y, z;
  double value;
  bool operator==(const Voxel&) const = default;
};

std::vector<Voxel> voxelsOf(const std::string& path) {
  auto file = pack::openFile(path);
  EXPECT_TRUE(file.isOk()) << path;
  std::vector<Voxel> out;
  if (!file) return out;
  format::VoxelLocator(*file).forEachVoxel([&](uint32_t x, uint32_t y, uint32_t z, uint64_t i) {
    out.push_back({x, y, z, file->value(i)});
  });
  return out;
}

// A 20x18x16 i16 volume with negative values, and spacing 0.5, 1, 2.
std::vector<int16_t> writeRaw(const std::string& path) {
  std::vector<int16_t> v(20 * 18 * 16);
  for (size_t i = 0; i < v.size(); ++i) {
    const int x = int(i % 20), y = int(i / 20 % 18), z = int(i / 360);
    v[i] = int16_t((x - 10) * (y - 9) * 3 + z * 7 - 40);
  }
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * 2));
  return v;
}

// writeRaw's volume as dir/v.vxl, keeping [-50, 60].
std::vector<int16_t> convertSample(const TempDir& dir) {
  const std::vector<int16_t> source = writeRaw(dir.file("v.raw"));
  auto r =
      runVoxlink({"convert", dir.file("v.raw"), "--dims", "20,18,16", "--type", "i16", "--spacing",
                  "0.5,1,2", "--threshold", "-50,60", "-o", dir.file("v.vxl"), "-q"});
  EXPECT_EQ(r.status, 0) << r.err;
  return source;
}

TEST(CliExport, DenseNrrdKeepsTypeSpacingAndFill) {
  TempDir dir;
  const std::vector<int16_t> source = convertSample(dir);
  auto r = runVoxlink({"export", dir.file("v.vxl"), "-o", dir.file("v.nrrd"), "--fill", "-999"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("filled with -999"), std::string::npos) << r.out;

  auto volume = sources::openVolume(dir.file("v.nrrd"));
  ASSERT_TRUE(volume.isOk()) << volume.message();
  const sources::VolumeInfo& info = (*volume)->info();
  EXPECT_EQ(info.type, ScalarType::kI16);
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{20, 18, 16}));
  EXPECT_EQ(info.spacing, (std::array<double, 3>{0.5, 1, 2}));
  auto bytes = sources::readAll(**volume);
  ASSERT_TRUE(bytes.isOk());
  ASSERT_EQ(bytes->size(), source.size() * 2);
  const auto* dense = reinterpret_cast<const int16_t*>(bytes->data());
  size_t kept = 0;
  for (size_t i = 0; i < source.size(); ++i) {
    const bool keep = source[i] >= -50 && source[i] <= 60;
    kept += keep;
    ASSERT_EQ(dense[i], keep ? source[i] : -999) << "voxel " << i;
  }
  EXPECT_GT(kept, 100u);
  EXPECT_LT(kept, source.size() / 2);
}

TEST(CliExport, FootRoundTripsThroughNrrd) {
  VOXLINK_REQUIRE_DATA("ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd");
  TempDir dir;
  auto r = runVoxlink({"convert", dataPath("ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd"),
                       "--threshold", "60", "-o", dir.file("foot.vxl"), "-q"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"export", dir.file("foot.vxl"), "-o", dir.file("foot_kept.nrrd")});
  ASSERT_EQ(r.status, 0) << r.err;
  const uint64_t bytes = std::filesystem::file_size(dir.file("foot_kept.nrrd"));
  EXPECT_GT(bytes, 256u * 256 * 256);         // u8 data, as the source
  EXPECT_LT(bytes, 256u * 256 * 256 + 1024);  // and a short header
  r = runVoxlink({"convert", dir.file("foot_kept.nrrd"), "--threshold", "60", "-o",
                  dir.file("again.vxl"), "-q"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<Voxel> first = voxelsOf(dir.file("foot.vxl"));
  EXPECT_GT(first.size(), 1000000u);
  EXPECT_TRUE(first == voxelsOf(dir.file("again.vxl")));
}

TEST(CliExport, RawPlusDetachedHeaderHoldsTheSameVolume) {
  TempDir dir;
  const std::vector<int16_t> source = convertSample(dir);
  auto r = runVoxlink({"export", dir.file("v.vxl"), "-o", dir.file("a.nrrd"), "--fill", "-7"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"export", dir.file("v.vxl"), "-o", dir.file("kept.nhdr"), "--fill", "-7"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("(header + .raw)"), std::string::npos) << r.out;
  // The .raw is the bare data: exactly the attached file's data, readable with dims and type.
  EXPECT_EQ(std::filesystem::file_size(dir.file("kept.raw")), source.size() * 2);
  auto attached = sources::openVolume(dir.file("a.nrrd"));
  auto detached = sources::openVolume(dir.file("kept.nhdr"));
  ASSERT_TRUE(attached.isOk()) << attached.message();
  ASSERT_TRUE(detached.isOk()) << detached.message();
  EXPECT_EQ((*detached)->info().spacing, (std::array<double, 3>{0.5, 1, 2}));
  EXPECT_EQ(*sources::readAll(**detached), *sources::readAll(**attached));
  EXPECT_EQ(*sources::readAll(**detached), readBytes(dir.file("kept.raw")));
  // A raw name that is the input itself is refused, and nothing is written.
  std::filesystem::copy_file(dir.file("v.vxl"), dir.file("x.raw"));
  r = runVoxlink({"export", dir.file("x.raw"), "-o", dir.file("x.nhdr")});
  EXPECT_NE(r.status, 0);
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.nhdr")));
}

// Output names in capitals pick the same formats: FOOT.NRRD is a NRRD file to every peer tool.
TEST(CliExport, ExtensionsIgnoreCase) {
  TempDir dir;
  convertSample(dir);
  auto r = runVoxlink({"export", dir.file("v.vxl"), "-o", dir.file("lower.nrrd")});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"export", dir.file("v.vxl"), "-o", dir.file("UPPER.NRRD")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(readBytes(dir.file("UPPER.NRRD")), readBytes(dir.file("lower.nrrd")));
  r = runVoxlink({"export", dir.file("v.vxl"), "-o", dir.file("KEPT.Nhdr")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("(header + .raw)"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir.file("KEPT.raw")));
  r = runVoxlink({"export", dir.file("v.vxl"), "-o", dir.file("V.VDB")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("grids 'values' and 'gradient'"), std::string::npos) << r.out;
  r = runVoxlink({"export", dir.file("v.vxl"), "-o", dir.file("v.NRRDX")});
  EXPECT_EQ(r.status, 2) << r.err;  // a usage error
  EXPECT_NE(r.err.find("unknown export format"), std::string::npos) << r.err;
}

TEST(CliExport, BadFillPathOrFileLeavesNothing) {
  TempDir dir;
  writeRaw(dir.file("v.raw"));
  auto r = runVoxlink({"convert", dir.file("v.raw"), "--dims", "20,18,16", "--type", "i16",
                       "--threshold", "0", "-o", dir.file("v.vxl"), "-q"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"export", dir.file("v.vxl"), "-o", dir.file("out.nrrd"), "--fill", "40000"});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("out.nrrd: --fill 40000 does not fit the source type i16"),
            std::string::npos)
      << r.err;
  r = runVoxlink({"export", dir.file("v.vxl"), "-o", dir.file("out.nrrd"), "--fill", "nan"});
  EXPECT_NE(r.status, 0);
  r = runVoxlink({"export", dir.file("v.vxl"), "-o", dir.file("out.nrrd"), "--fill", "2.5"});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("out.nrrd: --fill 2.5 is not a whole number, and the source type i16 "
                       "holds only whole numbers"),
            std::string::npos)
      << r.err;
  r = runVoxlink(
      {"export", dir.file("v.vxl"), "-o", dir.file("out.nrrd"), "--fill", "2147483647.5"});
  EXPECT_NE(r.err.find("--fill 2147483647.5 does not fit"), std::string::npos) << r.err;
  r = runVoxlink({"export", dir.file("v.vxl"), "-o", dir.file("missing/out.nrrd")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("missing"), std::string::npos) << r.err;
  r = runVoxlink({"export", dir.file("v.vxl"), "-o", dir.file("out.png")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("out.png: unknown export format"), std::string::npos) << r.err;
  // A file that fails validation: refused with the validator's message.
  std::filesystem::copy_file(dir.file("v.vxl"), dir.file("bad.vxl"));
  {
    std::fstream f(dir.file("bad.vxl"), std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(-20, std::ios::end);
    f.put('\x5a');
  }
  const auto good = runVoxlink({"validate", dir.file("bad.vxl")});
  ASSERT_NE(good.status, 0);
  r = runVoxlink({"export", dir.file("bad.vxl"), "-o", dir.file("out.nrrd")});
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(r.err, good.err);
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_TRUE(entry.path().extension() != ".nrrd" &&
                entry.path().filename().string().rfind(".vl-", 0) != 0)
        << entry.path();
}

// A full disk (writes past 1000 bytes fail with EFBIG): every writer reports it and leaves
// nothing. OpenVDB's own file writer did not check its stream, so `.vdb` export printed success
// over a cut-off file.
TEST(CliExport, FullDiskFailsEveryWriterCleanly) {
  TempDir dir;
  convertSample(dir);
  RunOptions full;
  full.fileSizeBytes = 1000;
  const std::vector<std::vector<std::string>> commands = {
      {"export", dir.file("v.vxl"), "-o", dir.file("out/v.vdb")},
      {"export", dir.file("v.vxl"), "-o", dir.file("out/v.nrrd")},
      {"export", dir.file("v.vxl"), "-o", dir.file("out/v.nhdr")},
      {"pack", dir.file("v.vxl"), "-o", dir.file("out/p.vxl")},
      {"convert", dir.file("v.raw"), "--dims", "20,18,16", "--type", "i16", "--threshold", "0",
       "-o", dir.file("out/c.vxl")},
  };
  std::filesystem::create_directory(dir.file("out"));
  for (const auto& command : commands) {
    const auto r = runVoxlink(command, full);
    EXPECT_NE(r.status, 0) << command[0] << " " << command.back() << ": " << r.out;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    // The error names the output, not its temporary (the data file for .nhdr).
    const std::string named =
        command.back().ends_with(".nhdr") ? dir.file("out/v.raw") : command.back();
    EXPECT_EQ(r.err.find("voxlink: " + named + ": "), 0u) << r.err;
    EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
    EXPECT_EQ(listDir(dir.file("out")), std::vector<std::string>{}) << command.back();
  }
}

// A valid file whose dense grid is far too large for memory (65536 x 65536 x 8 u16, one voxel
// stored): the export fails with one line naming the file, and leaves no temporary behind,
// instead of dying of an uncaught std::bad_alloc with its temporaries on disk.
TEST(CliExport, DenseGridTooLargeForMemoryFailsCleanly) {
  if (!addressSpaceLimitsWork()) GTEST_SKIP() << "AddressSanitizer cannot run under ulimit -v";
  TempDir dir;
  format::VolumeDescription d;
  d.dims = {65536, 65536, 8};
  d.valueType = StoredType::kU16;
  d.sourceType = ScalarType::kU16;
  format::BrickedVolumeBuilder builder(d);
  builder.add(5, 6, 7, 1000, 0);
  auto volume = builder.build();
  ASSERT_TRUE(volume) << volume.message();
  ASSERT_TRUE(format::writeBrickedVolume(dir.file("wide.vxl"), *volume).isOk());
  RunOptions limited;
  limited.addressSpaceBytes = uint64_t{8} << 30;  // the layer alone needs 64 GiB
  limited.timeoutSeconds = 120;
  for (const char* out : {"wide.nrrd", "wide.nhdr"}) {
    const auto r = runVoxlink({"export", dir.file("wide.vxl"), "-o", dir.file(out)}, limited);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("wide.vxl: a layer of bricks (65536 x 65536 x 8 u16 voxels, "
                         "68719476736 bytes) does not fit in memory"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"wide.vxl"});
}

}  // namespace
}  // namespace voxlink::testing
