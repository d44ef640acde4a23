// SPDX-License-Identifier: BSD-3-Clause
#include "base/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "base/regular_file.h"

namespace voxlink {
inline namespace base {
namespace {

size_t pageSize() {
  static const size_t size = static_cast<size_t>(sysconf(_SC_PAGESIZE));
  return size;
}

}  // namespace

Result<MappedFile> MappedFile::open(const std::string& path) {
  // O_NONBLOCK: a FIFO must not block open(); it is refused below, regular files mmap as usual.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return makeError(ErrorCode::kIo, path, ": cannot open: ", std::strerror(errno));
  struct stat st {};
  if (fstat(fd, &st) != 0) {
    const int e = errno;
    ::close(fd);
    return makeError(ErrorCode::kIo, path, ": cannot stat: ", std::strerror(e));
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    if (Status s = requireRegularFile(path); !s) return s.error();  // names what it is
    return makeError(ErrorCode::kIo, path, ": not a regular file");
  }
  MappedFile file;
  file.size_ = static_cast<size_t>(st.st_size);
  if (file.size_ > 0) {
    void* p = mmap(nullptr, file.size_, PROT_READ, MAP_SHARED, fd, 0);
    if (p == MAP_FAILED) {
      const int e = errno;
      ::close(fd);
      return makeError(ErrorCode::kIo, path, ": cannot map ", file.size_,
                       " bytes: ", std::strerror(e));
    }
    file.data_ = static_cast<const uint8_t*>(p);
  }
  ::close(fd);  // the mapping keeps the file alive
  return file;
}

MappedFile::MappedFile(MappedFile&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)) {}

MappedFile& MappedFile::operator=(MappedFile&& other) noexcept {
  if (this != &other) {
    if (data_) munmap(const_cast<uint8_t*>(data_), size_);
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
  }
  return *this;
}

MappedFile::~MappedFile() {
  if (data_) munmap(const_cast<uint8_t*>(data_), size_);
}

void MappedFile::release(size_t offset, size_t bytes) const {
  if (!data_ || offset >= size_) return;
  // Only whole pages inside the range may be dropped.
  const size_t page = pageSize();
  const size_t begin = (offset + page - 1) / page * page;
  const size_t end = std::min(size_, offset + bytes) / page * page;
  if (end > begin) madvise(const_cast<uint8_t*>(data_) + begin, end - begin, MADV_DONTNEED);
}

void MappedFile::willNeed(size_t offset, size_t bytes) const {
  if (!data_ || offset >= size_) return;
  const size_t page = pageSize();
  const size_t begin = offset / page * page;
  const size_t end = std::min(size_, offset + bytes);
  if (end <= begin) return;
#ifdef MADV_POPULATE_READ
  // Map the whole range into the page tables in one call (Linux 5.14+) instead of taking a
  // fault per 64 KiB while scanning; falls back to read-ahead on older kernels.
  if (madvise(const_cast<uint8_t*>(data_) + begin, end - begin, MADV_POPULATE_READ) == 0) return;
#endif
  madvise(const_cast<uint8_t*>(data_) + begin, end - begin, MADV_WILLNEED);
}

}  // namespace base
}  // namespace voxlink
