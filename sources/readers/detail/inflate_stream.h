// SPDX-License-Identifier: BSD-3-Clause
// Sequential zlib/gzip decoding of one file region with bounded memory: the compressed data of
// gzip NRRD files, zlib MetaImage files and .nii.gz files, decoded slice by slice.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "base/error.h"

namespace voxlink::sources {

class InflateStream {
 public:
  // Decodes the stream that starts at byte `offset` of `path` and runs to the end of the file.
  // zlib and gzip framing are told apart by the first bytes; concatenated gzip members are read
  // as one stream. `label` starts every error message (e.g. "LIDC2.nhdr: data file 'x.gz'").
  static Result<std::unique_ptr<InflateStream>> open(const std::string& path, uint64_t offset,
                                                     std::string label);
  ~InflateStream();
  InflateStream(const InflateStream&) = delete;
  InflateStream& operator=(const InflateStream&) = delete;

  // The decoded size the header promises; only used to word messages.
  void setExpectedSize(uint64_t bytes) { expected_ = bytes; }

  // Decodes exactly `bytes` more bytes. kTruncated when the stream ends first, kCorrupt when
  // zlib rejects the data.
  Status read(void* dst, uint64_t bytes);
  Status skip(uint64_t bytes);
  // Back to the first decoded byte.
  Status rewind();
  // Succeeds when no decoded byte is left; kSizeMismatch when the stream holds more data than
  // the header describes.
  Status expectEnd();
  uint64_t position() const { return produced_; }

 private:
  InflateStream() = default;
  Status start();
  // Decodes up to `bytes`; fewer only when the stream has ended.
  Result<uint64_t> decode(uint8_t* dst, uint64_t bytes);
  Result<bool> fillInput();
  Result<bool> anotherGzipMemberFollows();
  Status checkNothingTrails();

  std::string path_;
  std::string label_;
  uint64_t offset_ = 0;
  std::FILE* file_ = nullptr;
  struct ZState;
  std::unique_ptr<ZState> z_;
  std::vector<uint8_t> input_;
  bool fileDone_ = false;
  bool streamDone_ = false;
  uint64_t produced_ = 0;
  uint64_t expected_ = 0;
};

}  // namespace voxlink::sources
