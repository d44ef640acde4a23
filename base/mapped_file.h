// SPDX-License-Identifier: BSD-3-Clause
// Read-only memory mapping of a whole file (POSIX mmap), moved, never copied.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "base/error.h"

namespace voxlink {
inline namespace base {

class MappedFile {
 public:
  MappedFile() = default;
  static Result<MappedFile> open(const std::string& path);
  MappedFile(MappedFile&& other) noexcept;
  MappedFile& operator=(MappedFile&& other) noexcept;
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  ~MappedFile();

  const uint8_t* data() const { return data_; }
  size_t size() const { return size_; }
  // Tells the kernel these mapped pages are no longer needed, so they leave this process's
  // resident set (the file's page cache is untouched). Keeps streaming memory bounded.
  void release(size_t offset, size_t bytes) const;
  // Maps the range in ahead of use (prefaulted where the kernel can).
  void willNeed(size_t offset, size_t bytes) const;

 private:
  const uint8_t* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace base
}  // namespace voxlink
