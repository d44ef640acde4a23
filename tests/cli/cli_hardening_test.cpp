// SPDX-License-Identifier: BSD-3-Clause
// Hostile input through the command line, one test per class of defect: sizes that overflow,
// .vxl files that fail validation, outputs that must not be overwritten, non-regular inputs,
// and messages. Every failure is one line on stderr and a non-zero exit status.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <thread>

#include "base/crc32c.h"
#include "format/voxlink_file.h"
#include "pack/open_file.h"
#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

int lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

void expectOneLineFailure(const CommandResult& r, const std::vector<std::string>& mentions) {
  EXPECT_NE(r.status, 0);
  EXPECT_LT(r.status, 128) << "killed by a signal: " << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  for (const std::string& m : mentions) EXPECT_NE(r.err.find(m), std::string::npos) << r.err;
}

TEST(CliHardening, StatsRefusesDimsBeyondThePerAxisLimit) {
  TempDir dir;
  writeBytes(dir.file("empty.raw"), {});
  // 2^67 bytes of f64, 0 modulo 2^64: used to pass the size check and crash in stats.
  auto r = runVoxlink(
      {"stats", dir.file("empty.raw"), "--dims", "4194304,2097152,2097152", "--type", "f64"});
  expectOneLineFailure(r, {"empty.raw", "--dims", "65536"});
  r = runVoxlink({"convert", dir.file("empty.raw"), "--dims", "4194304,2097152,2097152", "--type",
                  "f64", "--keep-all", "-o", dir.file("o.vxl")});
  expectOneLineFailure(r, {"empty.raw", "--dims", "65536"});
}

// A 20^3 raw volume of `type` whose every voxel is `value` (or a ramp when `ramp`).
template <class T>
std::string rawVolume(const TempDir& dir, const std::string& name, T value, bool ramp = false) {
  std::vector<uint8_t> bytes(8000 * sizeof(T));
  for (size_t i = 0; i < 8000; ++i) {
    const T v = ramp ? static_cast<T>(i % 251) : value;
    std::memcpy(bytes.data() + i * sizeof(T), &v, sizeof(T));
  }
  writeBytes(dir.file(name), bytes);
  return dir.file(name);
}

// A valid .vxl converted from a 20^3 u8 ramp.
std::string convertedFile(const TempDir& dir, const std::string& name = "ok.vxl") {
  const std::string raw = rawVolume<uint8_t>(dir, "ramp.raw", 0, true);
  const auto r = runVoxlink({"convert", raw, "--dims", "20,20,20", "--type", "u8", "--threshold",
                             "100", "-o", dir.file(name), "-q"});
  EXPECT_EQ(r.status, 0) << r.err;
  return dir.file(name);
}

bool anyTempLeft(const TempDir& dir) {
  for (const std::string& name : listDir(dir.path()))
    if (name.starts_with(".vl-") || name.find(".tmp") != std::string::npos) return true;
  return false;
}

// Every command that reads a .vxl refuses what `validate` refuses, with validate's message.
void expectRefusedLikeValidate(const TempDir& dir, const std::string& file) {
  const auto v = runVoxlink({"validate", file});
  ASSERT_NE(v.status, 0);
  for (std::vector<std::string> args :
       {std::vector<std::string>{"info", file, "--no-vdb"},
        {"info", file},
        {"render", file, "-o", dir.file("r.png"), "--size", "32x32"}}) {
    SCOPED_TRACE(args[0]);
    const auto r = runVoxlink(args);
    EXPECT_EQ(r.status, v.status);
    EXPECT_EQ(r.err, v.err);
    EXPECT_FALSE(std::filesystem::exists(dir.file("r.png")));
  }
}

TEST(CliHardening, ReadersRefuseFilesThatFailValidation) {
  TempDir dir;
  const std::string file = convertedFile(dir);
  auto bytes = readBytes(file);
  auto parsed = pack::fileFromBytes(bytes, "x");
  ASSERT_TRUE(parsed) << parsed.message();
  const auto table = parsed->sectionTable();
  const uint64_t tableOffset = parsed->header().sectionTableOffset;
  size_t bocc = table.size();
  for (size_t i = 0; i < table.size(); ++i)
    if (table[i].id == static_cast<uint32_t>(format::SectionId::kBrickOccupancy)) bocc = i;
  ASSERT_LT(bocc, table.size());

  // A checksum that fails.
  auto flipped = bytes;
  flipped[table[bocc].offset] ^= 0x5a;
  writeBytes(dir.file("crc.vxl"), flipped);
  expectRefusedLikeValidate(dir, dir.file("crc.vxl"));

  // Occupancy damaged with its checksum recomputed: every brick marked occupied, so a renderer
  // trusting it would read past the per-brick sections.
  auto damaged = bytes;
  std::memset(damaged.data() + table[bocc].offset, 0xff, table[bocc].bytes);
  format::SectionEntry entry = table[bocc];
  entry.crc = base::crc32c(damaged.data() + entry.offset, entry.bytes);
  std::memcpy(damaged.data() + tableOffset + bocc * sizeof(entry), &entry, sizeof(entry));
  writeBytes(dir.file("bocc.vxl"), damaged);
  expectRefusedLikeValidate(dir, dir.file("bocc.vxl"));
}

TEST(CliHardening, ValidFilesWithExtremeValueRangesRender) {
  TempDir dir;
  // Every value 1e20: lo == hi and lo + 1 == lo.
  const std::string big = rawVolume<float>(dir, "big.raw", 1e20f);
  auto r = runVoxlink({"convert", big, "--dims", "20,20,20", "--type", "f32", "--keep-all", "-o",
                       dir.file("big.vxl"), "-q"});
  ASSERT_EQ(r.status, 0) << r.err;
  // Nothing kept: the stored range is empty (NaN in the header).
  const std::string ramp = rawVolume<float>(dir, "ramp.raw", 0.0f, true);
  r = runVoxlink({"convert", ramp, "--dims", "20,20,20", "--type", "f32", "--threshold", "1000",
                  "-o", dir.file("empty.vxl"), "-q"});
  ASSERT_EQ(r.status, 0) << r.err;
  // The same empty file with a NaN value range in its header (validate accepts it: no voxels).
  {
    auto bytes = readBytes(dir.file("empty.vxl"));
    format::FileHeader h;
    std::memcpy(&h, bytes.data(), sizeof h);
    ASSERT_EQ(h.voxelCount, 0u);
    h.valueMin = h.valueMax = std::numeric_limits<double>::quiet_NaN();
    h.headerCrc = 0;
    h.headerCrc = base::crc32c(&h, sizeof h);
    std::memcpy(bytes.data(), &h, sizeof h);
    writeBytes(dir.file("nan.vxl"), bytes);
  }
  for (const char* name : {"big.vxl", "empty.vxl", "nan.vxl"}) {
    SCOPED_TRACE(name);
    EXPECT_EQ(runVoxlink({"validate", dir.file(name)}).status, 0);
    r = runVoxlink({"render", dir.file(name), "-o", dir.file("out.png"), "--size", "32x32"});
    EXPECT_EQ(r.status, 0) << r.err;
    for (const char* preset : {"grayscale"}) {
      r = runVoxlink({"render", dir.file(name), "-o", dir.file("out.png"), "--size", "32x32",
                      "--tf-preset", preset});
      EXPECT_EQ(r.status, 0) << r.err;
    }
  }
}

TEST(CliHardening, F64BeyondFloatRangeConvertsToAValidFile) {
  TempDir dir;
  std::vector<uint8_t> bytes(8000 * 8);
  for (size_t i = 0; i < 8000; ++i) {
    const double v = (i % 2 ? 1e300 : -1e300) * double(i % 7 + 1) / 7;
    std::memcpy(bytes.data() + i * 8, &v, 8);
  }
  writeBytes(dir.file("huge.raw"), bytes);
  auto r = runVoxlink({"convert", dir.file("huge.raw"), "--dims", "20,20,20", "--type", "f64",
                       "--keep-all", "-o", dir.file("huge.vxl"), "-q"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"validate", dir.file("huge.vxl")});
  EXPECT_EQ(r.status, 0) << r.err;
  auto file = pack::openFile(dir.file("huge.vxl"));
  ASSERT_TRUE(file) << file.message();
  // Stored as f32 (scaled): the relative rounding error of f32.
  EXPECT_NEAR(file->header().valueMax, 1e300, 1e300 * 0x1p-24);
  EXPECT_NEAR(file->header().valueMin, -1e300, 1e300 * 0x1p-24);
}

TEST(CliHardening, OutputsThatMustNotBeReplaced) {
  TempDir dir;
  const std::string raw = rawVolume<uint8_t>(dir, "in.raw", 0, true);
  const std::vector<std::string> convert = {"convert", raw,          "--dims", "20,20,20", "--type",
                                            "u8",      "--keep-all", "-q",     "-o"};
  auto with = [&](const std::string& out) {
    auto args = convert;
    args.push_back(out);
    return runVoxlink(args);
  };
  // The input itself, by name and through a hard link.
  ASSERT_EQ(link(raw.c_str(), dir.file("alias.vxl").c_str()), 0);
  for (const std::string& out : {raw, dir.file("alias.vxl")}) {
    auto r = with(out);
    expectOneLineFailure(r, {"output is the input"});
    EXPECT_EQ(r.status, 2);
  }
  EXPECT_EQ(readBytes(raw).size(), 8000u);
  // Existing non-regular files.
  std::filesystem::create_directories(dir.file("folder.vxl"));
  auto r = with(dir.file("folder.vxl"));
  expectOneLineFailure(r, {"folder.vxl", "a directory"});
  EXPECT_TRUE(std::filesystem::is_directory(dir.file("folder.vxl")));
  r = with("/dev/null");
  expectOneLineFailure(r, {"/dev/null", "a device"});
  struct stat st {};
  ASSERT_EQ(stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  // render -o the .vxl it reads.
  const std::string vxl = convertedFile(dir);
  r = runVoxlink({"render", vxl, "-o", vxl, "--size", "16x16"});
  expectOneLineFailure(r, {"output is the input"});
  EXPECT_EQ(runVoxlink({"validate", vxl}).status, 0);
  EXPECT_FALSE(anyTempLeft(dir));
}

// krige writes two grids, each .nhdr with a .raw beside it: none of those files may be the input
// (a CSV named s.raw under -o s.nhdr was replaced), nor both grids one file (the values were
// lost under the variance).
TEST(CliHardening, KrigeOutputsSpareTheInputAndEachOther) {
  TempDir dir;
  {
    std::ofstream csv(dir.file("s.raw"));
    csv << "x,y,v\n0,0,1\n4,0,2\n0,4,3\n4,4,4\n2,2,5\n";
  }
  const std::vector<uint8_t> before = readBytes(dir.file("s.raw"));
  const std::vector<std::string> krige = {"krige",       dir.file("s.raw"), "--value", "v",
                                          "--variogram", "exp:range=4",     "--dims",  "4,4",
                                          "-o"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = krige;
    args.insert(args.end(), extra.begin(), extra.end());
    return runVoxlink(args);
  };
  auto r = with({dir.file("s.nhdr")});
  expectOneLineFailure(r, {"s.raw", "output is the input"});
  r = with({dir.file("k.nhdr"), "--variance-output", dir.file("s.nhdr")});
  expectOneLineFailure(r, {"s.raw", "output is the input"});
  r = with({dir.file("k.nhdr"), "--variance-output", dir.file("k.nhdr")});
  expectOneLineFailure(r, {"k.nhdr", "would both be written here"});
  EXPECT_EQ(readBytes(dir.file("s.raw")), before);
  EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"s.raw"});
  r = with({dir.file("k.nhdr")});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("k_variance.raw")));
}

TEST(CliHardening, LongestLegalOutputNameWorks) {
  TempDir dir;
  const std::string raw = rawVolume<uint8_t>(dir, "in.raw", 0, true);
  const std::string name = std::string(250, 'n') + ".vxl";  // 254 bytes: NAME_MAX is 255
  auto r = runVoxlink({"convert", raw, "--dims", "20,20,20", "--type", "u8", "--keep-all", "-q",
                       "-o", dir.file(name)});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(runVoxlink({"validate", dir.file(name)}).status, 0);
  const std::string png = std::string(250, 'p') + ".png";
  r = runVoxlink({"render", dir.file(name), "-o", dir.file(png), "--size", "16x16"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file(png)));
  EXPECT_FALSE(anyTempLeft(dir));
}

TEST(CliHardening, GridWritersIgnorePlantedSymlinksAndCommitHeaderWithData) {
  TempDir dir;
  writeBytes(dir.file("victim"), {1, 2, 3});
  // The names the writers used to open without O_EXCL.
  for (const char* planted : {"field.raw.tmp", "field.npy.tmp"})
    ASSERT_EQ(symlink(dir.file("victim").c_str(), dir.file(planted).c_str()), 0);
  for (const char* out : {"field.nhdr", "field.npy"}) {
    SCOPED_TRACE(out);
    auto r = runVoxlink({"grf", "--dims", "8,8,8", "-o", dir.file(out)});
    EXPECT_EQ(r.status, 0) << r.err;
  }
  EXPECT_EQ(readBytes(dir.file("victim")), (std::vector<uint8_t>{1, 2, 3}));
  EXPECT_EQ(readBytes(dir.file("field.raw")).size(), 8u * 8 * 8 * 8);
  EXPECT_TRUE(std::filesystem::exists(dir.file("field.nhdr")));
  for (const std::string& name : listDir(dir.path()))
    EXPECT_FALSE(name.starts_with(".vl-")) << name;
  // A failed run leaves neither header nor data.
  auto r = runVoxlink({"grf", "--dims", "8,8,8", "-o", "/dev/null/x.nhdr"});
  EXPECT_NE(r.status, 0);
}

TEST(CliHardening, TerminationSignalsRemoveTemporaries) {
  TempDir dir;
  for (int sig : {SIGTERM, SIGINT}) {
    SCOPED_TRACE(sig);
    // Large enough to run for a while; the temporary exists from the start.
    const int pid = startVoxlink({"grf", "--dims", "256,256,256", "-o", dir.file("g.nhdr")});
    bool sawTemp = false;
    for (int i = 0; i < 2000 && !sawTemp; ++i) {
      for (const std::string& name : listDir(dir.path())) sawTemp |= name.starts_with(".vl-");
      if (!sawTemp) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ASSERT_TRUE(sawTemp) << "the command never created its temporary file";
    kill(pid, sig);
    EXPECT_EQ(waitVoxlink(pid), 128 + sig);
    EXPECT_FALSE(anyTempLeft(dir));
    EXPECT_FALSE(std::filesystem::exists(dir.file("g.nhdr")));
  }
}

TEST(CliHardening, FifosAreRefusedNotWaitedOn) {
  TempDir dir;
  const std::string vxl = convertedFile(dir);
  ASSERT_EQ(mkfifo(dir.file("fifo.vxl").c_str(), 0600), 0);
  ASSERT_EQ(mkfifo(dir.file("tf.json").c_str(), 0600), 0);
  RunOptions timeout;
  timeout.timeoutSeconds = 60;
  for (std::vector<std::string> args :
       {std::vector<std::string>{"validate", dir.file("fifo.vxl")},
        {"info", dir.file("fifo.vxl"), "--no-vdb"},
        {"render", dir.file("fifo.vxl"), "-o", dir.file("o.png")},
        {"render", vxl, "-o", dir.file("o.png"), "--tf", dir.file("tf.json")},
        {"convert", dir.file("fifo.vxl"), "--format", "nrrd", "--keep-all", "-o",
         dir.file("o.vxl")},
        {"convert", dir.file("ramp.raw"), "--dims", "20,20,20", "--type", "u8", "--tf",
         dir.file("tf.json"), "-o", dir.file("o.vxl")},
        {"krige", dir.file("tf.json"), "--value", "v", "-o", dir.file("k.nhdr")}}) {
    SCOPED_TRACE(args[0] + " " + args[1]);
    const auto r = runVoxlink(args, timeout);
    expectOneLineFailure(r, {"FIFO"});
  }
}

TEST(CliHardening, OptionParserErrorsAreOneLineWithStatus2) {
  for (std::vector<std::string> args :
       {std::vector<std::string>{"convert", "--no-such-option"},
        {"convert"},
        {"stats", "x.raw", "--bins", "many"},
        {"stats", "x.raw", "--bins", "0"},
        {"stats", "x.raw", "--bins", "4294967295"},
        {"no-such-command"},
        {"convert", "in.raw", "--keep-outside", "-1,1", "--mean", "nan", "--sigma", "1", "-o", "o"},
        {"convert", "in.raw", "--keep-outside", "nan,1", "-o", "o"},
        {"grf", "--dims", "4,4,4", "--mean", "inf"}}) {
    SCOPED_TRACE(args[0] + " " + (args.size() > 1 ? args[1] : ""));
    const auto r = runVoxlink(args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_TRUE(r.err.starts_with("voxlink: ")) << r.err;
  }
  EXPECT_EQ(runVoxlink({"--help"}).status, 0);
  EXPECT_EQ(runVoxlink({"--version"}).status, 0);
}

TEST(CliHardening, LibraryComplaintsStayOnOneLine) {
  TempDir dir;
  std::vector<uint8_t> junk(400, 'j');
  writeBytes(dir.file("junk.nii"), junk);
  auto r = runVoxlink({"stats", dir.file("junk.nii")});
  expectOneLineFailure(r, {"junk.nii", "libnifti"});
  writeBytes(dir.file("junk.png"), junk);
  r = runVoxlink({"stats", dir.file("junk.png"), "--format", "image-stack"});
  expectOneLineFailure(r, {"junk.png"});
}

TEST(CliHardening, StandardOutputWriteErrorsFail) {
  TempDir dir;
  const std::string raw = rawVolume<uint8_t>(dir, "in.raw", 0, true);
  RunOptions full;
  full.stdoutPath = "/dev/full";
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this machine";
  auto r = runVoxlink({"stats", raw, "--dims", "20,20,20", "--type", "u8"}, full);
  expectOneLineFailure(r, {"standard output", "write failed"});
  const std::string vxl = convertedFile(dir);
  r = runVoxlink({"info", vxl, "--no-vdb"}, full);
  expectOneLineFailure(r, {"standard output"});
  r = runVoxlink({"validate", vxl}, full);
  expectOneLineFailure(r, {"standard output"});
}

// A full disk: a small tmpfs. CI runs as root but may not be allowed to mount; then this skips.
TEST(CliHardening, FullDiskFailsWithoutLeavingAFile) {
  TempDir dir;
  const std::string mnt = dir.file("small");
  std::filesystem::create_directories(mnt);
  if (mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=64k") != 0)
    GTEST_SKIP() << "cannot mount a small tmpfs here (" << std::strerror(errno)
                 << "); the full-disk test needs CAP_SYS_ADMIN";
  struct Unmount {
    std::string path;
    ~Unmount() { umount2(path.c_str(), MNT_DETACH); }
  } unmount{mnt};
  // 100^3 u8 noise keeps every voxel: ~4 MB of output into 64 KiB.
  std::vector<uint8_t> noise(1000000);
  uint32_t x = 1;
  for (uint8_t& v : noise) v = static_cast<uint8_t>((x = x * 1664525u + 1013904223u) >> 24);
  writeBytes(dir.file("noise.raw"), noise);
  auto r = runVoxlink({"convert", dir.file("noise.raw"), "--dims", "100,100,100", "--type", "u8",
                       "--keep-all", "-q", "-o", mnt + "/o.vxl"});
  expectOneLineFailure(r, {"o.vxl"});
  // Fill the file system to the last block, then render a PNG into it.
  {
    std::FILE* filler = std::fopen((mnt + "/filler").c_str(), "wb");
    ASSERT_TRUE(filler);
    std::setvbuf(filler, nullptr, _IONBF, 0);
    const std::vector<uint8_t> block(4096, 1);
    while (std::fwrite(block.data(), 1, block.size(), filler) == block.size()) {
    }
    while (std::fwrite(block.data(), 1, 1, filler) == 1) {
    }
    std::fclose(filler);
  }
  const std::string vxl = convertedFile(dir);
  r = runVoxlink({"render", vxl, "-o", mnt + "/o.png", "--size", "256x256"});
  expectOneLineFailure(r, {"o.png"});
  for (const std::string& name : listDir(mnt)) EXPECT_EQ(name, "filler");
}

}  // namespace
}  // namespace voxlink::testing
