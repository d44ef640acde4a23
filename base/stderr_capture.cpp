// SPDX-License-Identifier: BSD-3-Clause
#include "base/stderr_capture.h"

#include <unistd.h>

#include <cstdio>
#include <mutex>

namespace voxlink {
inline namespace base {
namespace {

std::mutex mutex;
int users = 0;
int savedFd = -1;
std::FILE* sink = nullptr;

}  // namespace

StderrCapture::StderrCapture() {
  std::lock_guard lock(mutex);
  if (users++ > 0) return;
  std::fflush(stderr);
  sink = std::tmpfile();
  if (!sink) return;
  savedFd = ::dup(2);
  if (savedFd < 0 || ::dup2(fileno(sink), 2) < 0) {
    if (savedFd >= 0) ::close(savedFd);
    savedFd = -1;
    std::fclose(sink);
    sink = nullptr;
  }
}

StderrCapture::~StderrCapture() {
  std::lock_guard lock(mutex);
  if (--users > 0) return;
  std::fflush(stderr);
  if (savedFd >= 0) {
    ::dup2(savedFd, 2);
    ::close(savedFd);
    savedFd = -1;
  }
  if (sink) std::fclose(sink);
  sink = nullptr;
}

std::string StderrCapture::firstLine() const {
  std::lock_guard lock(mutex);
  std::fflush(stderr);
  if (!sink) return "";
  char buf[512];
  const ssize_t n = ::pread(fileno(sink), buf, sizeof buf, 0);
  if (n <= 0) return "";
  const std::string text(buf, static_cast<size_t>(n));
  size_t start = text.find_first_not_of("\n\r");
  if (start == std::string::npos) return "";
  const size_t end = text.find_first_of("\n\r", start);
  return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

}  // namespace base
}  // namespace voxlink
