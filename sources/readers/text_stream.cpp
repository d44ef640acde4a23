// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/text_stream.h"

#include <zip.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include "base/mapped_file.h"

namespace voxlink::sources {
namespace {

bool endsWithZip(const std::string& path) {
  if (path.size() < 4) return false;
  std::string tail = path.substr(path.size() - 4);
  std::transform(tail.begin(), tail.end(), tail.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return tail == ".zip";
}

std::string_view stripCr(std::string_view s) {
  if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
  return s;
}

class MappedTextStream final : public TextStream {
 public:
  MappedTextStream(base::MappedFile file, std::string name) : file_(std::move(file)) {
    name_ = std::move(name);
  }
  Result<bool> nextLine(std::string_view& line) override {
    const char* data = reinterpret_cast<const char*>(file_.data());
    if (pos_ >= file_.size()) return false;
    const void* nl = std::memchr(data + pos_, '\n', file_.size() - pos_);
    const size_t end = nl ? static_cast<size_t>(static_cast<const char*>(nl) - data) : file_.size();
    line = stripCr(std::string_view(data + pos_, end - pos_));
    pos_ = end + 1;
    ++line_;
    return true;
  }
  Status rewind() override {
    pos_ = 0;
    line_ = 0;
    return Status::ok();
  }

 private:
  base::MappedFile file_;
  size_t pos_ = 0;
};

class ZipTextStream final : public TextStream {
 public:
  static Result<std::unique_ptr<TextStream>> open(const std::string& path) {
    int err = 0;
    zip_t* archive = zip_open(path.c_str(), ZIP_RDONLY, &err);
    if (!archive) {
      zip_error_t e;
      zip_error_init_with_code(&e, err);
      std::string why = zip_error_strerror(&e);
      zip_error_fini(&e);
      return makeError(ErrorCode::kIo, path, ": cannot open as a zip archive: ", why);
    }
    std::unique_ptr<ZipTextStream> s(new ZipTextStream);
    s->archive_ = archive;
    std::vector<zip_uint64_t> files;
    std::string names;
    const zip_int64_t entries = zip_get_num_entries(archive, 0);
    for (zip_int64_t i = 0; i < entries; ++i) {
      const char* n = zip_get_name(archive, static_cast<zip_uint64_t>(i), 0);
      if (!n || std::string(n).ends_with("/")) continue;
      files.push_back(static_cast<zip_uint64_t>(i));
      names += (names.empty() ? "" : ", ") + std::string(n);
    }
    if (files.size() != 1)
      return makeError(
          ErrorCode::kUnsupported, path, ": zip archive holds ", files.size(), " files (", names,
          "); only an archive with exactly one member is read: unzip it and name the file");
    s->index_ = files[0];
    s->name_ = path + ":" + names;
    VOXLINK_RETURN_IF_ERROR(s->rewind());
    return std::unique_ptr<TextStream>(std::move(s));
  }
  ~ZipTextStream() override {
    if (member_) zip_fclose(member_);
    if (archive_) zip_discard(archive_);
  }
  Result<bool> nextLine(std::string_view& line) override {
    for (;;) {
      const size_t nl = buffer_.find('\n', pos_);
      if (nl != std::string::npos || eof_) {
        if (pos_ >= buffer_.size() && eof_) return false;
        const size_t end = nl == std::string::npos ? buffer_.size() : nl;
        line = stripCr(std::string_view(buffer_).substr(pos_, end - pos_));
        pos_ = end + 1;
        ++line_;
        return true;
      }
      buffer_.erase(0, pos_);
      pos_ = 0;
      char chunk[1 << 16];
      const zip_int64_t got = zip_fread(member_, chunk, sizeof chunk);
      if (got < 0)
        return makeError(ErrorCode::kCorrupt, name_,
                         ": decompression failed: ", zip_file_strerror(member_));
      if (got == 0) eof_ = true;
      buffer_.append(chunk, static_cast<size_t>(got));
    }
  }
  Status rewind() override {
    if (member_) zip_fclose(member_);
    member_ = zip_fopen_index(archive_, index_, 0);
    if (!member_)
      return makeError(ErrorCode::kUnsupported, name_,
                       ": cannot open the member: ", zip_strerror(archive_));
    buffer_.clear();
    pos_ = 0;
    eof_ = false;
    line_ = 0;
    return Status::ok();
  }

 private:
  ZipTextStream() = default;
  zip_t* archive_ = nullptr;
  zip_file_t* member_ = nullptr;
  zip_uint64_t index_ = 0;
  std::string buffer_;
  size_t pos_ = 0;
  bool eof_ = false;
};

}  // namespace

Result<std::unique_ptr<TextStream>> openTextStream(const std::string& path) {
  if (endsWithZip(path)) return ZipTextStream::open(path);
  VOXLINK_ASSIGN_OR_RETURN(base::MappedFile file, base::MappedFile::open(path));
  return std::unique_ptr<TextStream>(new MappedTextStream(std::move(file), path));
}

}  // namespace voxlink::sources
