// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/inflate_stream.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>

#include "base/regular_file.h"

namespace voxlink::sources {

struct InflateStream::ZState {
  z_stream s{};
  bool initialized = false;
  ~ZState() {
    if (initialized) inflateEnd(&s);
  }
};

namespace {
constexpr size_t kInputChunk = size_t{1} << 20;
constexpr uInt kMaxOutputChunk = uInt{1} << 30;
}  // namespace

Result<std::unique_ptr<InflateStream>> InflateStream::open(const std::string& path, uint64_t offset,
                                                           std::string label) {
  std::unique_ptr<InflateStream> stream(new InflateStream());
  stream->path_ = path;
  stream->label_ = std::move(label);
  stream->offset_ = offset;
  VOXLINK_RETURN_IF_ERROR(base::requireRegularFile(path, "data file"));
  stream->file_ = std::fopen(path.c_str(), "rb");
  if (!stream->file_) return makeError(ErrorCode::kIo, stream->label_, ": cannot open ", path);
  stream->input_.resize(kInputChunk);
  VOXLINK_RETURN_IF_ERROR(stream->start());
  return stream;
}

InflateStream::~InflateStream() {
  if (file_) std::fclose(file_);
}

Status InflateStream::start() {
  if (fseeko(file_, static_cast<off_t>(offset_), SEEK_SET) != 0)
    return makeError(ErrorCode::kIo, label_, ": cannot seek to byte ", offset_, " of ", path_);
  z_ = std::make_unique<ZState>();
  // 15 window bits + 32: accept zlib and gzip headers alike.
  if (inflateInit2(&z_->s, 15 + 32) != Z_OK)
    return makeError(ErrorCode::kIo, label_, ": zlib could not start a decoder");
  z_->initialized = true;
  fileDone_ = false;
  streamDone_ = false;
  produced_ = 0;
  return Status::ok();
}

Status InflateStream::rewind() { return start(); }

Result<bool> InflateStream::fillInput() {
  if (z_->s.avail_in > 0) return true;
  if (fileDone_) return false;
  const size_t got = std::fread(input_.data(), 1, input_.size(), file_);
  if (got < input_.size()) {
    if (std::ferror(file_)) return makeError(ErrorCode::kIo, label_, ": read error in ", path_);
    fileDone_ = true;
  }
  z_->s.next_in = input_.data();
  z_->s.avail_in = static_cast<uInt>(got);
  return got > 0;
}

Result<bool> InflateStream::anotherGzipMemberFollows() {
  VOXLINK_ASSIGN_OR_RETURN(bool more, fillInput());
  if (!more) return false;
  if (z_->s.avail_in == 1 && !fileDone_) {
    // Keep the one byte and pull the next chunk behind it so the magic can be checked.
    input_[0] = z_->s.next_in[0];
    const size_t got = std::fread(input_.data() + 1, 1, input_.size() - 1, file_);
    if (got < input_.size() - 1) fileDone_ = true;
    z_->s.next_in = input_.data();
    z_->s.avail_in = static_cast<uInt>(got + 1);
  }
  return z_->s.avail_in >= 2 && z_->s.next_in[0] == 0x1f && z_->s.next_in[1] == 0x8b;
}

// After the last member only zero padding may follow (gzip itself warns about anything else);
// other bytes mean a damaged or concatenated file and are an error, not silently dropped.
Status InflateStream::checkNothingTrails() {
  uint64_t seen = 0;
  for (;;) {
    for (uInt i = 0; i < z_->s.avail_in; ++i)
      if (z_->s.next_in[i] != 0)
        return makeError(ErrorCode::kCorrupt, label_,
                         ": trailing garbage after the end of the compressed stream (a non-zero "
                         "byte ",
                         seen + i, " bytes past it, after ", produced_, " decoded bytes)");
    seen += z_->s.avail_in;
    z_->s.avail_in = 0;
    VOXLINK_ASSIGN_OR_RETURN(bool more, fillInput());
    if (!more) return Status::ok();
  }
}

Result<uint64_t> InflateStream::decode(uint8_t* dst, uint64_t bytes) {
  uint64_t done = 0;
  while (done < bytes && !streamDone_) {
    VOXLINK_ASSIGN_OR_RETURN(bool haveInput, fillInput());
    z_->s.next_out = dst + done;
    z_->s.avail_out = static_cast<uInt>(std::min<uint64_t>(bytes - done, kMaxOutputChunk));
    const uInt before = z_->s.avail_out;
    const int rc = inflate(&z_->s, Z_NO_FLUSH);
    const uint64_t made = before - z_->s.avail_out;
    done += made;
    produced_ += made;
    if (rc == Z_STREAM_END) {
      VOXLINK_ASSIGN_OR_RETURN(bool another, anotherGzipMemberFollows());
      if (another) {
        inflateReset(&z_->s);
      } else {
        streamDone_ = true;
        VOXLINK_RETURN_IF_ERROR(checkNothingTrails());
      }
      continue;
    }
    if (rc == Z_DATA_ERROR || rc == Z_NEED_DICT || rc == Z_STREAM_ERROR)
      return makeError(ErrorCode::kCorrupt, label_, ": compressed data is corrupt after ",
                       produced_, " decoded bytes (zlib: ", z_->s.msg ? z_->s.msg : "invalid data",
                       ")");
    if (rc == Z_MEM_ERROR)
      return makeError(ErrorCode::kTooLarge, label_, ": zlib ran out of memory");
    if (rc == Z_BUF_ERROR && !haveInput && made == 0)
      return makeError(ErrorCode::kTruncated, label_, ": compressed stream is cut off after ",
                       produced_, " decoded bytes",
                       expected_ ? cat(" of ", expected_, " the header describes") : "");
  }
  return done;
}

Status InflateStream::read(void* dst, uint64_t bytes) {
  VOXLINK_ASSIGN_OR_RETURN(uint64_t got, decode(static_cast<uint8_t*>(dst), bytes));
  if (got < bytes)
    return makeError(ErrorCode::kTruncated, label_, ": compressed stream ends after ", produced_,
                     " decoded bytes",
                     expected_ ? cat(" of ", expected_, " the header describes") : "");
  return Status::ok();
}

Status InflateStream::skip(uint64_t bytes) {
  std::vector<uint8_t> scratch(std::min<uint64_t>(bytes, uint64_t{1} << 20));
  while (bytes > 0) {
    const uint64_t n = std::min<uint64_t>(bytes, scratch.size());
    VOXLINK_RETURN_IF_ERROR(read(scratch.data(), n));
    bytes -= n;
  }
  return Status::ok();
}

Status InflateStream::expectEnd() {
  const uint64_t at = produced_;
  std::vector<uint8_t> scratch(1);
  VOXLINK_ASSIGN_OR_RETURN(uint64_t got, decode(scratch.data(), 1));
  if (got == 0) return Status::ok();
  // More data: decode on (bounded) so a damaged stream is reported as corrupt (its check value
  // fails at the end) rather than as a size disagreement.
  const uint64_t limit = std::max<uint64_t>(at, uint64_t{64} << 20);
  scratch.resize(std::min<uint64_t>(limit, uint64_t{1} << 20));
  uint64_t extra = got;
  while (got > 0 && extra < limit) {
    VOXLINK_ASSIGN_OR_RETURN(got, decode(scratch.data(), scratch.size()));
    extra += got;
  }
  return makeError(ErrorCode::kSizeMismatch, label_, ": compressed stream holds ",
                   got == 0 ? "" : "more than ", at + extra, " bytes, the header describes ", at);
}

}  // namespace voxlink::sources
