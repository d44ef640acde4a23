// SPDX-License-Identifier: BSD-3-Clause
#include "base/regular_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace voxlink {
inline namespace base {
namespace {

const char* kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  return "not a regular file";
}

Status notRegular(const std::string& path, std::string_view what, mode_t mode) {
  return makeError(ErrorCode::kIo, path, ": ", what, " is ", kindOf(mode),
                   ", expected a regular file");
}

// An fd of a regular file opened without waiting for a writer, or an error.
Result<int> openRegular(const std::string& path, std::string_view what, uint64_t& size) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
    return makeError(ErrorCode::kIo, path, ": cannot open ", what, ": ", std::strerror(errno));
  struct stat st {};
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    const mode_t mode = st.st_mode;
    ::close(fd);
    return notRegular(path, what, mode);
  }
  size = static_cast<uint64_t>(st.st_size);
  return fd;
}

Result<std::string> readUpTo(const std::string& path, uint64_t maxBytes, std::string_view what,
                             bool refuseLarger) {
  uint64_t size = 0;
  VOXLINK_ASSIGN_OR_RETURN(const int fd, openRegular(path, what, size));
  if (refuseLarger && size > maxBytes) {
    ::close(fd);
    return makeError(ErrorCode::kTooLarge, path, ": ", what, " of ", size, " bytes, more than ",
                     maxBytes);
  }
  std::string text(static_cast<size_t>(std::min(size, maxBytes)), '\0');
  size_t got = 0;
  while (got < text.size()) {
    const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int e = errno;
      ::close(fd);
      return makeError(ErrorCode::kIo, path, ": cannot read ", what, ": ", std::strerror(e));
    }
    if (n == 0) break;  // the file shrank
    got += static_cast<size_t>(n);
  }
  ::close(fd);
  text.resize(got);
  return text;
}

}  // namespace

Status requireRegularFile(const std::string& path, std::string_view what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    return makeError(ErrorCode::kIo, path, ": cannot open ", what, ": ", std::strerror(errno));
  if (!S_ISREG(st.st_mode)) return notRegular(path, what, st.st_mode);
  return Status::ok();
}

Result<std::string> readRegularFile(const std::string& path, uint64_t maxBytes,
                                    std::string_view what) {
  return readUpTo(path, maxBytes, what, true);
}

Result<std::string> readRegularFilePrefix(const std::string& path, uint64_t maxBytes,
                                          std::string_view what) {
  return readUpTo(path, maxBytes, what, false);
}

}  // namespace base
}  // namespace voxlink
