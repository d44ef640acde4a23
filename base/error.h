// SPDX-License-Identifier: BSD-3-Clause
// Errors returned by every VoxLink library: a code a test can assert on and a one-line message
// that names the file, the field and the bad value. Libraries return them; executables decide
// how to report them.
#pragma once

#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <variant>

#include "base/check.h"

namespace voxlink {
inline namespace base {

enum class ErrorCode {
  kInvalidArgument,  // a caller-supplied option is out of range or inconsistent
  kIo,               // the operating system refused to open, read or write
  kTruncated,        // the data ends before the header says it should
  kSizeMismatch,     // a header states sizes that disagree with the data
  kCorrupt,          // a checksum or structural invariant does not hold
  kUnsupported,      // a valid but unsupported type, encoding, version or layout
  kNotAVoxLinkFile,  // the magic number is wrong
  kByteOrder,        // the file was written with the other byte order
  kNonFinite,        // NaN or infinity where a finite value is required
  kTooLarge,         // a size exceeds the limits of the format or of this machine
  kCancelled,        // the caller asked to stop
};

const char* errorCodeName(ErrorCode code);

struct Error {
  ErrorCode code;
  std::string message;
};

// Concatenates streamable values; keeps call sites short without <format> (not in g++ 12).
template <class... Args>
std::string cat(Args&&... args) {
  std::ostringstream out;
  (out << ... << std::forward<Args>(args));
  return out.str();
}

template <class... Args>
Error makeError(ErrorCode code, Args&&... args) {
  return Error{code, cat(std::forward<Args>(args)...)};
}

// Success or an Error.
class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(Error error) : error_(std::move(error)) {}
  static Status ok() { return {}; }
  bool isOk() const { return !error_.has_value(); }
  explicit operator bool() const { return isOk(); }
  // Only on a failed Status (checked: an OK one has no error to give).
  const Error& error() const {
    VOXLINK_CHECK(error_.has_value(), "Status::error() called on an OK status");
    return *error_;
  }
  const std::string& message() const { return error().message; }
  ErrorCode code() const { return error().code; }

 private:
  std::optional<Error> error_;
};

// A value or an Error.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}
  Result(Error error) : v_(std::move(error)) {}
  // Only from a failed Status (checked: an OK one carries no value to hold).
  Result(Status status) : v_(errorOf(status)) {}
  bool isOk() const { return std::holds_alternative<T>(v_); }
  explicit operator bool() const { return isOk(); }
  T& value() & { return std::get<T>(v_); }
  const T& value() const& { return std::get<T>(v_); }
  T&& value() && { return std::get<T>(std::move(v_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() { return value(); }
  const Error& error() const { return std::get<Error>(v_); }
  const std::string& message() const { return error().message; }
  ErrorCode code() const { return error().code; }
  Status status() const { return isOk() ? Status() : Status(error()); }

 private:
  static Error errorOf(const Status& status) {
    VOXLINK_CHECK(!status.isOk(), "Result built from an OK Status");
    return status.error();
  }

  std::variant<T, Error> v_;
};

}  // namespace base
}  // namespace voxlink

// Returns early from the calling function when a Status/Result holds an error.
#define VOXLINK_RETURN_IF_ERROR(expr)                     \
  do {                                                    \
    auto voxlink_status_ = (expr);                        \
    if (!voxlink_status_) return voxlink_status_.error(); \
  } while (0)

#define VOXLINK_CONCAT_INNER(a, b) a##b
#define VOXLINK_CONCAT(a, b) VOXLINK_CONCAT_INNER(a, b)
#define VOXLINK_ASSIGN_OR_RETURN_IMPL(tmp, lhs, expr) \
  auto tmp = (expr);                                  \
  if (!tmp) return tmp.error();                       \
  lhs = std::move(tmp).value()
#define VOXLINK_ASSIGN_OR_RETURN(lhs, expr) \
  VOXLINK_ASSIGN_OR_RETURN_IMPL(VOXLINK_CONCAT(voxlink_result_, __LINE__), lhs, expr)
