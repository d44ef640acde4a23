// SPDX-License-Identifier: BSD-3-Clause
// Faults during a conversion: the process killed (SIGKILL, SIGTERM), an output folder it may not
// write, and a file past 4 GiB (64-bit offsets). Whatever happens, the output path holds either
// nothing or a complete file, and no temporary is left where the OS lets us avoid one.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>

#include "format/voxlink_file.h"
#include "pack/open_file.h"
#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

namespace fs = std::filesystem;

// Whether this file system gives unnamed temporaries (O_TMPFILE); where it does not, the writer
// falls back to a named .vl-XXXXXX temporary, which only kill -9 can leave behind.
bool unnamedTempsWork(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_TMPFILE | O_RDWR, 0600);
  if (fd < 0) return false;
  ::close(fd);
  return true;
}

// 256^3 u8 noise: every voxel kept makes a ~50 MB output that takes a while to write.
std::string noiseVolume(const TempDir& dir) {
  std::vector<uint8_t> noise(256 * 256 * 256);
  uint32_t x = 7;
  for (uint8_t& v : noise) v = static_cast<uint8_t>((x = x * 1664525u + 1013904223u) >> 24);
  writeBytes(dir.file("noise.raw"), noise);
  return dir.file("noise.raw");
}

// Waits until `pid` holds a file open in `outDir` (its output's temporary); false if the
// process ended first.
bool waitForOutputOpen(int pid, const fs::path& outDir) {
  const fs::path fds = "/proc/" + std::to_string(pid) + "/fd";
  const std::string prefix = outDir.string() + "/";
  for (int i = 0; i < 20000; ++i) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(fds, ec)) {
      const fs::path target = fs::read_symlink(entry.path(), ec);
      if (!ec && target.string().starts_with(prefix)) return true;
    }
    if (ec && !fs::exists(fds)) return false;
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

void expectKilledMidConversionLeavesNothing(int sig) {
  TempDir in;
  TempDir out;
  const std::string raw = noiseVolume(in);
  const int pid = startVoxlink({"convert", raw, "--dims", "256,256,256", "--type", "u8",
                                "--keep-all", "--threads", "1", "-q", "-o", out.file("n.vxl")});
  ASSERT_TRUE(waitForOutputOpen(pid, out.path()))
      << "the conversion ended before it opened its output";
  kill(pid, sig);
  EXPECT_EQ(waitVoxlink(pid), 128 + sig);
  EXPECT_FALSE(fs::exists(out.file("n.vxl")));
  const std::vector<std::string> left = listDir(out.path());
  if (sig == SIGKILL && !unnamedTempsWork(out.path())) {
    // Named temporaries cannot be removed by a process killed outright.
    ASSERT_LE(left.size(), 1u);
    if (!left.empty()) {
      EXPECT_TRUE(left[0].starts_with(".vl-")) << left[0];
    }
  } else {
    EXPECT_TRUE(left.empty()) << left.size() << " files left, the first " << left[0];
  }
}

TEST(CliFaults, KillNineMidConversionLeavesNothing) {
  expectKilledMidConversionLeavesNothing(SIGKILL);
}

TEST(CliFaults, SigtermMidConversionLeavesNothing) {
  expectKilledMidConversionLeavesNothing(SIGTERM);
}

// An output folder the command may not write to: a one-line error naming the output, nothing
// written. Root ignores permission bits, so as root the folder is a read-only tmpfs (skipped
// where mounting is not permitted).
TEST(CliFaults, ReadOnlyOutputFolderIsOneLineError) {
  TempDir dir;
  const std::string folder = dir.file("ro");
  fs::create_directories(folder);
  struct Unmount {
    std::string path;
    bool mounted = false;
    ~Unmount() {
      if (mounted) umount2(path.c_str(), MNT_DETACH);
      ::chmod(path.c_str(), 0755);
    }
  } cleanup{folder};
  if (geteuid() == 0) {
    if (mount("tmpfs", folder.c_str(), "tmpfs", MS_RDONLY, "size=64k") != 0)
      GTEST_SKIP() << "running as root and cannot mount a read-only tmpfs (" << std::strerror(errno)
                   << "); root may write any folder";
    cleanup.mounted = true;
  } else {
    ASSERT_EQ(::chmod(folder.c_str(), 0555), 0);
  }
  std::vector<uint8_t> ramp(20 * 20 * 20);
  for (size_t i = 0; i < ramp.size(); ++i) ramp[i] = static_cast<uint8_t>(i % 251);
  writeBytes(dir.file("ramp.raw"), ramp);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"convert", dir.file("ramp.raw"), "--dims", "20,20,20", "--type",
                                 "u8", "--keep-all", "-q", "-o", folder + "/o.vxl"},
        {"grf", "--dims", "8,8,8", "-o", folder + "/g.nhdr"}}) {
    SCOPED_TRACE(args[0]);
    const CommandResult r = runVoxlink(args);
    EXPECT_NE(r.status, 0);
    EXPECT_LT(r.status, 128) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(folder), std::string::npos) << r.err;
  }
  EXPECT_TRUE(listDir(folder).empty());
}

// A file past 4 GiB: 1152^3 voxels all kept, u8 values and 16-bit gradients (about 4.6 GB), so
// the gradient section ends and the section table starts beyond 2^32. The input is a sparse
// file of zeros (no disk); the output is real. Opt-in: it writes 4.6 GB and takes minutes.
TEST(CliFaults, FileBeyondFourGiBRoundTrips) {
  const char* optIn = std::getenv("VOXLINK_LARGE_TESTS");
  if (optIn == nullptr || std::string(optIn) != "1")
    GTEST_SKIP() << "writes a 4.6 GB file; run with VOXLINK_LARGE_TESTS=1";
  TempDir dir;
  constexpr uint64_t kSide = 1152;
  const std::string raw = dir.file("zeros.raw");
  {
    const int fd = ::open(raw.c_str(), O_CREAT | O_WRONLY | O_TRUNC, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(ftruncate(fd, static_cast<off_t>(kSide * kSide * kSide)), 0);
    ::close(fd);
  }
  const std::string side = std::to_string(kSide);
  const std::string vxl = dir.file("big.vxl");
  CommandResult r = runVoxlink({"convert", raw, "--dims", side + "," + side + "," + side, "--type",
                                "u8", "--keep-all", "-q", "-o", vxl});
  ASSERT_EQ(r.status, 0) << r.err;
  fs::remove(raw);
  EXPECT_GT(fs::file_size(vxl), uint64_t{1} << 32);
  r = runVoxlink({"validate", vxl});
  EXPECT_EQ(r.status, 0) << r.err;
  auto file = pack::openFile(vxl);
  ASSERT_TRUE(file) << file.message();
  EXPECT_EQ(file->voxelCount(), kSide * kSide * kSide);
  EXPECT_GT(file->header().sectionTableOffset, uint64_t{1} << 32);
  uint64_t end = 0;
  for (const auto& entry : file->sectionTable()) end = std::max(end, entry.offset + entry.bytes);
  EXPECT_GT(end, uint64_t{1} << 32);
  // The gradient codes run past 4 GiB; their span must not have wrapped.
  EXPECT_GE(file->gradientCodes().size(), kSide * kSide * kSide);
}

}  // namespace
}  // namespace voxlink::testing
