// SPDX-License-Identifier: BSD-3-Clause
#include "base/output_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "base/temp_janitor.h"

namespace voxlink {
inline namespace base {
namespace {

constexpr size_t kSlots = 32;
// 0 free, 1 being filled or emptied, 2 holds a path the handler may unlink.
std::array<std::atomic<int>, kSlots> slotState{};
std::array<std::array<char, PATH_MAX>, kSlots> slotPath{};

void onSignal(int sig) {
  for (size_t i = 0; i < kSlots; ++i)
    if (slotState[i].load() == 2) ::unlink(slotPath[i].data());
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

// A fresh ".vl-XXXXXX<suffix>" name in `dir` (letters and digits at random). Callers register
// it for cleanup before creating the file, so that no signal finds a temporary on disk that the
// handler does not know about, and create it exclusively, trying another name if it is taken.
std::string randomTempName(const std::filesystem::path& dir, std::string_view suffix) {
  static constexpr char kChars[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
  static std::atomic<uint64_t> calls{0};
  uint64_t state =
      static_cast<uint64_t>(::getpid()) * 0x9E3779B97F4A7C15ull ^
      static_cast<uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count()) ^
      (calls.fetch_add(1) + 1) * 0xD1B54A32D192ED03ull;
  std::string name = ".vl-XXXXXX";
  for (size_t i = 4; i < name.size(); ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    name[i] = kChars[(state >> 33) % (sizeof(kChars) - 1)];
  }
  return (dir / name).string() + std::string(suffix);
}

const char* kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Whether `path` is the file `out` describes (device and inode: hard links and other names too).
bool isFile(const struct stat& out, const std::string& path) {
  struct stat in {};
  return ::stat(path.c_str(), &in) == 0 && in.st_dev == out.st_dev && in.st_ino == out.st_ino;
}

}  // namespace

Status checkOutputTarget(const std::string& target, const std::vector<std::string>& inputs) {
  // Refused before any work: an empty name only failed at the final rename.
  if (target.empty())
    return makeError(ErrorCode::kInvalidArgument, "output path is empty; give a file name");
  struct stat out {};
  if (::stat(target.c_str(), &out) != 0) return Status::ok();  // does not exist yet
  if (!S_ISREG(out.st_mode))
    return makeError(ErrorCode::kInvalidArgument, target, ": output exists and is ",
                     kindOf(out.st_mode), "; give a file name to write");
  for (const std::string& input : inputs)
    if (isFile(out, input))
      return makeError(ErrorCode::kInvalidArgument, target, ": output is the input file ", input,
                       "; give another output name");
  return Status::ok();
}

Status checkOutputTarget(const std::string& target, const std::string& input,
                         const std::vector<std::string>& files) {
  VOXLINK_RETURN_IF_ERROR(checkOutputTarget(target, {input}));
  struct stat out {};
  if (::stat(target.c_str(), &out) != 0) return Status::ok();
  for (const std::string& file : files)
    if (isFile(out, file))
      return makeError(ErrorCode::kInvalidArgument, target, ": output is ", file,
                       ", a file the input ", input, " reads; give another output name");
  return Status::ok();
}

Result<TempFile> createTempBeside(const std::string& target, std::string_view suffix) {
  VOXLINK_RETURN_IF_ERROR(checkOutputTarget(target));
  std::filesystem::path dir = std::filesystem::path(target).parent_path();
  if (dir.empty()) dir = ".";
  // Short on purpose: the name must fit NAME_MAX whatever the target's name is.
  int error = EEXIST;
  for (int attempt = 0; attempt < 100 && error == EEXIST; ++attempt) {
    std::string path = randomTempName(dir, suffix);
    registerTempForCleanup(path);  // first: a signal from now on removes it
    const int fd = ::open(path.c_str(), O_CREAT | O_EXCL | O_RDWR | O_CLOEXEC, 0644);
    if (fd >= 0) {
      fchmod(fd, 0644);  // whatever the umask: outputs are ordinary readable files
      return TempFile{fd, path};
    }
    error = errno;
    unregisterTempForCleanup(path);
  }
  return makeError(ErrorCode::kIo, target, ": cannot create a temporary file in ", dir.string(),
                   ": ", std::strerror(error));
}

Result<TempFile> createUnnamedTempBeside(const std::string& target) {
  VOXLINK_RETURN_IF_ERROR(checkOutputTarget(target));
  std::filesystem::path dir = std::filesystem::path(target).parent_path();
  if (dir.empty()) dir = ".";
  // linkat needs the fd's /proc link (AT_EMPTY_PATH would need CAP_DAC_READ_SEARCH).
  if (::access("/proc/self/fd", X_OK) == 0) {
    const int fd = ::open(dir.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0644);
    if (fd >= 0) return TempFile{fd, "/proc/self/fd/" + std::to_string(fd), true};
    // Unsupported here (EOPNOTSUPP, EISDIR on old kernels): a named temporary instead; other
    // errors (permissions, a full disk) are reported by that attempt in the same words.
  }
  return createTempBeside(target);
}

Status commitTempFile(const TempFile& temp, const std::string& target) {
  if (!temp.unnamed) {
    if (::close(temp.fd) != 0) {
      const int e = errno;
      discardTemp(temp.path);
      return makeError(ErrorCode::kIo, target, ": closing the output failed: ", std::strerror(e));
    }
    return commitTemp(temp.path, target);
  }
  std::filesystem::path dir = std::filesystem::path(target).parent_path();
  if (dir.empty()) dir = ".";
  // A fresh name for the link, registered before linkat makes it (see randomTempName).
  std::string linked;
  int linkErrno = EEXIST;
  for (int attempt = 0; attempt < 100 && linkErrno == EEXIST; ++attempt) {
    linked = randomTempName(dir, "");
    registerTempForCleanup(linked);
    linkErrno =
        ::linkat(AT_FDCWD, temp.path.c_str(), AT_FDCWD, linked.c_str(), AT_SYMLINK_FOLLOW) == 0
            ? 0
            : errno;
    if (linkErrno != 0) unregisterTempForCleanup(linked);
  }
  if (linkErrno != 0) {
    ::close(temp.fd);
    return makeError(ErrorCode::kIo, target, ": cannot link the finished file into ", dir.string(),
                     ": ", std::strerror(linkErrno));
  }
  if (::close(temp.fd) != 0) {
    const int e = errno;
    discardTemp(linked);
    return makeError(ErrorCode::kIo, target, ": closing the output failed: ", std::strerror(e));
  }
  return commitTemp(linked, target);
}

Status writeWholeFile(const std::string& target, std::span<const uint8_t> bytes) {
  const std::span<const uint8_t> pieces[1] = {bytes};
  return writeWholeFile(target, pieces);
}

Status writeWholeFile(const std::string& target, std::span<const std::span<const uint8_t>> pieces) {
  VOXLINK_ASSIGN_OR_RETURN(TempFile temp, createUnnamedTempBeside(target));
  for (const std::span<const uint8_t> piece : pieces) {
    const uint8_t* p = piece.data();
    uint64_t left = piece.size();
    while (left > 0) {
      const ssize_t n = ::write(temp.fd, p, std::min<uint64_t>(left, uint64_t{1} << 30));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const std::string why = n < 0 ? std::strerror(errno) : "no progress";
        ::close(temp.fd);
        if (!temp.unnamed) discardTemp(temp.path);
        return makeError(ErrorCode::kIo, target, ": write failed: ", why);
      }
      p += n;
      left -= static_cast<uint64_t>(n);
    }
  }
  return commitTempFile(temp, target);
}

Status commitTemp(const std::string& tempPath, const std::string& target) {
  if (std::rename(tempPath.c_str(), target.c_str()) != 0) {
    const int e = errno;
    discardTemp(tempPath);
    return makeError(ErrorCode::kIo, target,
                     ": cannot move the finished file into place: ", std::strerror(e));
  }
  unregisterTempForCleanup(tempPath);
  return Status::ok();
}

void discardTemp(const std::string& tempPath) {
  ::unlink(tempPath.c_str());
  unregisterTempForCleanup(tempPath);
}

void registerTempForCleanup(const std::string& path) {
  if (path.size() >= PATH_MAX) return;
  for (size_t i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!slotState[i].compare_exchange_strong(expected, 1)) continue;
    std::memcpy(slotPath[i].data(), path.c_str(), path.size() + 1);
    slotState[i].store(2);
    tellTempJanitor('+', path);
    return;
  }
}

void unregisterTempForCleanup(const std::string& path) {
  for (size_t i = 0; i < kSlots; ++i) {
    int expected = 2;
    if (!slotState[i].compare_exchange_strong(expected, 1)) continue;
    if (path == slotPath[i].data()) {
      slotState[i].store(0);
      tellTempJanitor('-', path);
      return;
    }
    slotState[i].store(2);
  }
}

void removeRegisteredTemps() {
  for (size_t i = 0; i < kSlots; ++i) {
    int expected = 2;
    if (!slotState[i].compare_exchange_strong(expected, 1)) continue;
    ::unlink(slotPath[i].data());
    slotState[i].store(0);
  }
}

void removeTempsOnSignals() {
  struct sigaction sa {};
  sa.sa_handler = onSignal;
  sigemptyset(&sa.sa_mask);
  // SIGABRT too: an exception that escapes a thread, or a failed check, ends in abort().
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGABRT}) sigaction(sig, &sa, nullptr);
}

}  // namespace base
}  // namespace voxlink
