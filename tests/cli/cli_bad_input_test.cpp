// SPDX-License-Identifier: BSD-3-Clause
// Bad input through the command line: one line on stderr naming the file and the field, a
// non-zero exit status, and no output file (not even a temporary one) left behind.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include "format/voxlink_file.h"
#include "pack/open_file.h"
#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

int lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

class CliBadInput : public ::testing::Test {
 protected:
  // A 20x20x20 u8 raw volume.
  std::string rawVolume(size_t bytes = 8000) {
    std::vector<uint8_t> data(bytes);
    for (size_t i = 0; i < data.size(); ++i) data[i] = static_cast<uint8_t>(i * 7);
    const std::string path = dir_.file("in.raw");
    writeBytes(path, data);
    return path;
  }
  // A valid VoxLink file converted from `raw`, or "" when the conversion failed.
  std::string convertedFile(const std::string& raw) {
    const std::string out = dir_.file("ok.vxl");
    const auto r = runVoxlink({"convert", raw, "--dims", "20,20,20", "--type", "u8", "--threshold",
                               "100", "-o", out, "-q"});
    EXPECT_EQ(r.status, 0) << r.err;
    return r.status == 0 ? out : "";
  }
  void expectCleanFailure(const CommandResult& r, const std::string& mentions) {
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(mentions), std::string::npos) << r.err;
    for (const std::string& name : listDir(dir_.path()))
      EXPECT_EQ(name.find(".vxl"), std::string::npos) << "left behind: " << name;
  }
  TempDir dir_;
};

TEST_F(CliBadInput, TruncatedRawFile) {
  const std::string in = rawVolume(7999);
  auto r = runVoxlink({"convert", in, "--dims", "20,20,20", "--type", "u8", "--threshold", "10",
                       "-o", dir_.file("o.vxl")});
  expectCleanFailure(r, "in.raw: data:");
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
}

TEST_F(CliBadInput, WrongDims) {
  const std::string in = rawVolume();
  auto r = runVoxlink({"convert", in, "--dims", "20,20,19", "--type", "u8", "--threshold", "10",
                       "-o", dir_.file("o.vxl")});
  expectCleanFailure(r, "check --dims");
}

TEST_F(CliBadInput, UnsupportedTypeName) {
  const std::string in = rawVolume();
  auto r = runVoxlink({"convert", in, "--dims", "20,20,20", "--type", "u12", "--threshold", "10",
                       "-o", dir_.file("o.vxl")});
  expectCleanFailure(r, "--type u12");
  EXPECT_EQ(r.status, 2);
}

TEST_F(CliBadInput, NaNInFloatData) {
  std::vector<float> data(1000, 1.0f);
  data[123] = std::nanf("");
  std::vector<uint8_t> bytes(data.size() * 4);
  std::memcpy(bytes.data(), data.data(), bytes.size());
  writeBytes(dir_.file("f.raw"), bytes);
  auto r = runVoxlink({"convert", dir_.file("f.raw"), "--dims", "10,10,10", "--type", "f32",
                       "--keep-all", "-o", dir_.file("o.vxl")});
  expectCleanFailure(r, "f.raw: data: value nan at voxel (3, 2, 1)");
}

TEST_F(CliBadInput, OutputThatCannotBeWritten) {
  const std::string in = rawVolume();
  auto r = runVoxlink({"convert", in, "--dims", "20,20,20", "--type", "u8", "--threshold", "10",
                       "-o", dir_.file("nope/o.vxl")});
  expectCleanFailure(r, "nope/o.vxl: cannot create a temporary file");
  EXPECT_EQ(r.status, 3);
}

// A thread count meant as -1 or mistyped would start that many threads (100000 exhausted this
// machine's tasks); every command with --threads refuses it before starting any.
TEST_F(CliBadInput, AbsurdThreadCountsAreRefused) {
  const std::string in = rawVolume();
  expectCleanFailure(runVoxlink({"convert", in, "--dims", "20,20,20", "--type", "u8", "--threshold",
                                 "10", "--threads", "100000", "-o", dir_.file("o.vxl")}),
                     "--threads 100000 is more than 1024 threads");
  const auto grf =
      runVoxlink({"grf", "--dims", "8,8,8", "--threads", "1025", "-o", dir_.file("g.nhdr")});
  EXPECT_NE(grf.status, 0);
  EXPECT_EQ(lines(grf.err), 1) << grf.err;
  EXPECT_NE(grf.err.find("threads 1025 is more than 1024"), std::string::npos) << grf.err;
  EXPECT_FALSE(std::filesystem::exists(dir_.file("g.nhdr")));
  const std::string vxl = convertedFile(in);
  ASSERT_FALSE(vxl.empty());
  const auto pack = runVoxlink({"pack", vxl, "--threads", "4294967295", "-o", dir_.file("p.vxl")});
  EXPECT_NE(pack.status, 0);
  EXPECT_EQ(lines(pack.err), 1) << pack.err;
  EXPECT_NE(pack.err.find("--threads 4294967295 is more than 1024"), std::string::npos) << pack.err;
  EXPECT_FALSE(std::filesystem::exists(dir_.file("p.vxl")));
  // The limit itself is allowed.
  EXPECT_EQ(runVoxlink({"pack", vxl, "--threads", "1024", "-o", dir_.file("p.vxl"), "-q"}).status,
            0);
}

// Threads the system cannot start (here: 1000 stacks of 8 MB in a 4 GB address space, as under
// `ulimit -v` on a shared node) are left out; the command finishes with the others and writes
// the same bytes, instead of aborting or hanging.
TEST_F(CliBadInput, ThreadsThatCannotStartAreLeftOut) {
  if (!addressSpaceLimitsWork()) GTEST_SKIP() << "AddressSanitizer cannot run under ulimit -v";
  const std::string in = rawVolume();
  const auto convert = [&](const std::string& threads, const std::string& out) {
    RunOptions limited;
    limited.addressSpaceBytes = uint64_t{4} << 30;
    limited.timeoutSeconds = 60;
    return runVoxlink({"convert", in, "--dims", "20,20,20", "--type", "u8", "--threshold", "100",
                       "--threads", threads, "-o", dir_.file(out), "-q"},
                      limited);
  };
  const auto one = convert("1", "one.vxl");
  ASSERT_EQ(one.status, 0) << one.err;
  const auto many = convert("1000", "many.vxl");
  ASSERT_EQ(many.status, 0) << many.err;
  EXPECT_EQ(readBytes(dir_.file("one.vxl")), readBytes(dir_.file("many.vxl")));
  RunOptions limited;
  limited.addressSpaceBytes = uint64_t{4} << 30;
  limited.timeoutSeconds = 60;
  const auto pack = runVoxlink(
      {"pack", dir_.file("one.vxl"), "--threads", "1000", "-o", dir_.file("p.vxl"), "-q"}, limited);
  EXPECT_EQ(pack.status, 0) << pack.err;
  const auto unpack =
      runVoxlink({"unpack", dir_.file("p.vxl"), "-o", dir_.file("u.vxl"), "-q"}, limited);
  EXPECT_EQ(unpack.status, 0) << unpack.err;
  EXPECT_EQ(readBytes(dir_.file("one.vxl")), readBytes(dir_.file("u.vxl")));
}

TEST_F(CliBadInput, NoClassificationGiven) {
  const std::string in = rawVolume();
  auto r =
      runVoxlink({"convert", in, "--dims", "20,20,20", "--type", "u8", "-o", dir_.file("o.vxl")});
  expectCleanFailure(r, "say what to keep");
}

TEST_F(CliBadInput, DamagedVoxLinkFilesForInfoAndValidate) {
  const std::string in = rawVolume();
  const std::string out = convertedFile(in);
  ASSERT_FALSE(out.empty());
  auto bytes = readBytes(out);
  // Truncated file.
  writeBytes(dir_.file("cut.vxl"), std::vector<uint8_t>(bytes.begin(), bytes.begin() + 1000));
  auto r = runVoxlink({"validate", dir_.file("cut.vxl")});
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(lines(r.err), 1);
  EXPECT_NE(r.err.find("cut.vxl"), std::string::npos) << r.err;
  r = runVoxlink({"info", dir_.file("cut.vxl")});
  EXPECT_NE(r.status, 0);
  // One flipped byte inside the values.
  bytes[bytes.size() / 2] ^= 0x40;
  writeBytes(dir_.file("flip.vxl"), bytes);
  r = runVoxlink({"validate", dir_.file("flip.vxl")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("flip.vxl: section"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("checksum mismatch"), std::string::npos) << r.err;
  // Voxel bases pointing past the voxels: the header and table are fine, so the file opens,
  // and the OpenVDB comparison (which walks every voxel) must refuse it rather than crash.
  {
    auto file = pack::openFile(out);
    ASSERT_TRUE(file) << file.message();
    const format::SectionEntry* bvox = file->findSection(format::SectionId::kBrickVoxelBase);
    ASSERT_NE(bvox, nullptr);
    ASSERT_GE(bvox->bytes, 8u);
    auto damaged = readBytes(out);
    damaged[bvox->offset + 7] = 0x7F;  // the second base becomes huge
    writeBytes(dir_.file("bases.vxl"), damaged);
  }
  r = runVoxlink({"info", dir_.file("bases.vxl")});
  EXPECT_EQ(r.status, 1) << r.err;  // an error, not a signal
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("bases.vxl: section BVOX"), std::string::npos) << r.err;
  // Without the comparison too: every reader of a .vxl refuses what `validate` refuses.
  r = runVoxlink({"info", "--no-vdb", dir_.file("bases.vxl")});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.err, runVoxlink({"validate", dir_.file("bases.vxl")}).err);
  // Not a VoxLink file at all.
  r = runVoxlink({"info", in});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("header.magic"), std::string::npos) << r.err;
}

// Image sizes are parsed whole: sscanf's %u wrapped 4294967360 to 64 and read -5 as 4294967291.
TEST_F(CliBadInput, ImageSizesThatDoNotParseAreRefused) {
  const std::string vxl = convertedFile(rawVolume());
  ASSERT_FALSE(vxl.empty());
  if (runVoxlink({"render", "--help"}).status != 0) GTEST_SKIP() << "built without the viewer";
  for (const char* size : {"4294967360x4294967360", "4294967297x1", "-5x5", "5x+5", "16x", "x16",
                           "16x16x", "0x16", "16 x16", "16x16 ", "1e3x16"}) {
    const auto r = runVoxlink({"render", vxl, "-o", dir_.file("out.png"), "--size", size});
    EXPECT_EQ(r.status, 2) << size;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(std::string("--size: expected WxH such as 512x512, got '") + size + "'"),
              std::string::npos)
        << r.err;
  }
  EXPECT_TRUE(listDir(dir_.path()) == std::vector<std::string>({"in.raw", "ok.vxl"}) ||
              listDir(dir_.path()) == std::vector<std::string>({"ok.vxl", "in.raw"}));
}

// A rendered image is written under a temporary name and renamed: a failed write leaves
// nothing, a good one leaves exactly the image.
TEST_F(CliBadInput, RenderedImageIsWholeOrAbsent) {
  const std::string vxl = convertedFile(rawVolume());
  ASSERT_FALSE(vxl.empty());
  if (runVoxlink({"render", "--help"}).status != 0) GTEST_SKIP() << "built without the viewer";
  auto r = runVoxlink({"render", vxl, "-o", dir_.file("missing/out.png"), "--size", "16x16"});
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("missing/out.png"), std::string::npos) << r.err;
  r = runVoxlink({"render", vxl, "-o", dir_.file("out.png"), "--size", "16x16"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> images;
  for (const std::string& name : listDir(dir_.path()))
    if (name.find(".png") != std::string::npos) images.push_back(name);
  ASSERT_EQ(images.size(), 1u);
  EXPECT_NE(images[0].find("out.png"), std::string::npos);
}

// An MTL statement that assimp 5.2.5 writes through a null material (a SEGV before the check in
// geometry/mtl_file_check.cpp): the scene build names the MTL file and line, and writes nothing.
TEST_F(CliBadInput, SceneBuildRefusesATextureMapBeforeNewmtl) {
  const std::string obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string mtl = "# materials\nmap_Kd wood.png\nnewmtl wood\nKd 1 1 1\n";
  const std::string scene =
      R"({"grid": {"resolution": 16}, "objects": [{"type": "mesh", "file": "m.obj"}]})";
  writeBytes(dir_.file("m.obj"), std::vector<uint8_t>(obj.begin(), obj.end()));
  writeBytes(dir_.file("m.mtl"), std::vector<uint8_t>(mtl.begin(), mtl.end()));
  writeBytes(dir_.file("s.scene.json"), std::vector<uint8_t>(scene.begin(), scene.end()));
  auto r = runVoxlink({"scene", "build", dir_.file("s.scene.json"), "-o", dir_.file("o.vxl")});
  expectCleanFailure(r, "m.mtl: line 2: 'map_Kd' (texture map) before the first newmtl");
}

// A damaged header whose quoted value holds a newline and a stray byte still gives one line.
TEST_F(CliBadInput, DamagedHeaderTextIsEscapedIntoOneLine) {
  const std::string header = "{'descr': '<u2', 'fortran_order': Fal\ne\xF6, 'shape': (2, 2, 2), }";
  std::string npy = std::string("\x93NUMPY\x01\x00", 8);
  std::string padded = header + std::string(118 - 10 - 1 - header.size(), ' ') + "\n";
  npy += static_cast<char>(padded.size() & 0xFF);
  npy += static_cast<char>(padded.size() >> 8);
  npy += padded + std::string(16, '\0');
  writeBytes(dir_.file("bad.npy"), std::vector<uint8_t>(npy.begin(), npy.end()));
  auto r = runVoxlink({"convert", dir_.file("bad.npy"), "--keep-all", "-o", dir_.file("o.vxl")});
  expectCleanFailure(r, "bad.npy");
  EXPECT_NE(r.err.find("\\n"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\\xF6"), std::string::npos) << r.err;
}

// Random damage (cuts, flipped bytes in the header, the section table and the data) never
// crashes `info` or `validate`: each either succeeds (the damage hit padding or rewrote a byte
// with its own value) or fails with one line.
TEST_F(CliBadInput, RandomDamageNeverCrashesInfoOrValidate) {
  const std::string out = convertedFile(rawVolume());
  ASSERT_FALSE(out.empty());
  const auto original = readBytes(out);
  auto file = pack::openFile(out);
  ASSERT_TRUE(file) << file.message();
  const std::vector<format::SectionEntry> sections = file->sectionTable();
  std::mt19937 rng(2026);
  int failures = 0;
  for (int trial = 0; trial < 48; ++trial) {
    auto bytes = original;
    switch (trial % 3) {
      case 0:  // cut anywhere
        bytes.resize(rng() % bytes.size());
        break;
      case 1: {  // a few bytes of one section, each section in turn
        const format::SectionEntry& e = sections[(trial / 3) % sections.size()];
        for (int k = 0; k < 3 && e.bytes > 0; ++k)
          bytes[e.offset + rng() % e.bytes] = static_cast<uint8_t>(rng());
        break;
      }
      default:  // the header or the section table at the end
        for (int k = 0; k < 3; ++k) {
          const size_t i = rng() % 2 ? rng() % 256 : bytes.size() - 1 - rng() % 300;
          bytes[i] = static_cast<uint8_t>(rng());
        }
    }
    const std::string damaged = dir_.file("damaged.vxl");
    writeBytes(damaged, bytes);
    for (const char* command : {"validate", "info"}) {
      const auto r = runVoxlink({command, damaged});
      SCOPED_TRACE(std::string(command) + ", trial " + std::to_string(trial));
      EXPECT_LT(r.status, 128) << "killed by a signal";
      if (r.status != 0) {
        ++failures;
        EXPECT_EQ(lines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find("damaged.vxl"), std::string::npos) << r.err;
      }
    }
  }
  EXPECT_GT(failures, 60);  // most damage is detected
}

TEST_F(CliBadInput, ViewTimeThatIsNotANumberIsRefused) {
  // CLI11's range check lets "nan" through (no comparison holds); the animation was then
  // sampled at NaN, past its last key (before: the viewer opened and drew that pose).
  const std::string scene = dir_.file("a.scene.json");
  writeBytes(scene, std::vector<uint8_t>{'{', '}'});
  for (const char* time : {"nan", "-nan", "inf"}) {
    SCOPED_TRACE(time);
    expectCleanFailure(runVoxlink({"view", scene, "--time", time}), "--time");
  }
}

}  // namespace
}  // namespace voxlink::testing
