// SPDX-License-Identifier: BSD-3-Clause
#include "base/error.h"

namespace voxlink {
inline namespace base {

const char* errorCodeName(ErrorCode code) {
  switch (code) {
    case ErrorCode::kInvalidArgument:
      return "invalid-argument";
    case ErrorCode::kIo:
      return "io";
    case ErrorCode::kTruncated:
      return "truncated";
    case ErrorCode::kSizeMismatch:
      return "size-mismatch";
    case ErrorCode::kCorrupt:
      return "corrupt";
    case ErrorCode::kUnsupported:
      return "unsupported";
    case ErrorCode::kNotAVoxLinkFile:
      return "not-a-voxlink-file";
    case ErrorCode::kByteOrder:
      return "byte-order";
    case ErrorCode::kNonFinite:
      return "non-finite";
    case ErrorCode::kTooLarge:
      return "too-large";
    case ErrorCode::kCancelled:
      return "cancelled";
  }
  return "unknown";
}

}  // namespace base
}  // namespace voxlink
