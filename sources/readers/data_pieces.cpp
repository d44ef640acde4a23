// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/data_pieces.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "base/regular_file.h"
#include "sources/readers/detail/byte_order.h"
#include "sources/readers/detail/inflate_stream.h"
#include "sources/readers/raw_reader.h"

namespace voxlink::sources {
namespace {

namespace fs = std::filesystem;

// A missing data file, with a hint when a file beside it looks like the intended one
// ("HeadMRVolume.raw" named by a header, "vtk_HeadMRVolume.raw" on disk).
Error missingFile(const std::string& label, const std::string& path) {
  const fs::path p(path);
  std::string hint;
  std::error_code ec;
  if (fs::is_directory(p.parent_path(), ec)) {
    const std::string want = p.filename().string();
    for (const auto& entry : fs::directory_iterator(p.parent_path(), ec)) {
      const std::string name = entry.path().filename().string();
      if (name != want && name.size() > want.size() && name.ends_with(want)) {
        hint = cat(" (", name, " is there; the header may name it differently)");
        break;
      }
    }
  }
  return makeError(ErrorCode::kIo, label, ": ", path, " does not exist", hint);
}

// Byte offset just after `lines` newlines, counted from `from`.
Result<uint64_t> skipLines(const std::string& path, uint64_t from, uint64_t lines,
                           const std::string& label) {
  VOXLINK_RETURN_IF_ERROR(base::requireRegularFile(path, "data file"));
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return makeError(ErrorCode::kIo, label, ": cannot open ", path);
  uint64_t offset = from;
  uint64_t seen = 0;
  if (fseeko(f, static_cast<off_t>(from), SEEK_SET) == 0) {
    int c;
    while (seen < lines && (c = std::fgetc(f)) != EOF) {
      ++offset;
      if (c == '\n') ++seen;
    }
  }
  std::fclose(f);
  if (seen < lines)
    return makeError(ErrorCode::kTruncated, label, ": line skip ", lines, ": ", path, " has only ",
                     seen, " lines after byte ", from);
  return offset;
}

struct ResolvedPiece {
  DataPiece piece;
  uint64_t dataOffset = 0;  // raw: first data byte; deflate: first compressed byte
  uint32_t firstSlice = 0;
};

class PieceSource final : public VolumeSource {
 public:
  PieceSource(VolumeInfo info, std::vector<ResolvedPiece> pieces, PieceLayout layout)
      : pieces_(std::move(pieces)), layout_(std::move(layout)) {
    info_ = std::move(info);
    swap_ =
        scalarSize(info_.type) > 1 && ((layout_.endian == Endian::kLittle) != kHostIsLittleEndian);
  }
  ~PieceSource() override { closeFile(); }

  bool randomAccess() const override { return layout_.encoding == PieceEncoding::kRaw; }

  Status read(uint32_t z0, uint32_t count, void* dst) override {
    VOXLINK_RETURN_IF_ERROR(checkSliceRange(z0, count));
    auto* out = static_cast<uint8_t*>(dst);
    uint32_t z = z0;
    while (z < z0 + count) {
      const size_t p = pieceOf(z);
      const ResolvedPiece& rp = pieces_[p];
      const uint32_t inPiece = z - rp.firstSlice;
      const uint32_t n = std::min(z0 + count, rp.firstSlice + rp.piece.slices) - z;
      if (layout_.encoding == PieceEncoding::kRaw) {
        VOXLINK_RETURN_IF_ERROR(readRaw(p, inPiece, n, out));
      } else {
        VOXLINK_RETURN_IF_ERROR(readDeflate(p, z, inPiece, n, out));
      }
      out += uint64_t{n} * info_.sliceBytes();
      z += n;
    }
    if (swap_) swapBytesInPlace(dst, uint64_t{count} * info_.sliceVoxels(), scalarSize(info_.type));
    return Status::ok();
  }

  Status rewind() override {
    stream_.reset();
    nextSlice_ = 0;
    return Status::ok();
  }

 private:
  size_t pieceOf(uint32_t z) const {
    auto it =
        std::upper_bound(pieces_.begin(), pieces_.end(), z,
                         [](uint32_t v, const ResolvedPiece& rp) { return v < rp.firstSlice; });
    return static_cast<size_t>(it - pieces_.begin()) - 1;
  }

  void closeFile() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    fdPiece_ = SIZE_MAX;
  }

  Status readRaw(size_t p, uint32_t inPiece, uint32_t n, uint8_t* out) {
    const ResolvedPiece& rp = pieces_[p];
    if (fdPiece_ != p) {
      closeFile();
      VOXLINK_RETURN_IF_ERROR(base::requireRegularFile(rp.piece.path, "data file"));
      fd_ = ::open(rp.piece.path.c_str(), O_RDONLY | O_CLOEXEC);
      if (fd_ < 0) return makeError(ErrorCode::kIo, layout_.label, ": cannot open ", rp.piece.path);
      fdPiece_ = p;
    }
    uint64_t offset = rp.dataOffset + uint64_t{inPiece} * info_.sliceBytes();
    uint64_t left = uint64_t{n} * info_.sliceBytes();
    while (left > 0) {
      const ssize_t got = ::pread(fd_, out, std::min<uint64_t>(left, uint64_t{1} << 30),
                                  static_cast<off_t>(offset));
      if (got <= 0)
        return makeError(got == 0 ? ErrorCode::kTruncated : ErrorCode::kIo, layout_.label, ": ",
                         rp.piece.path, " ends or fails at byte ", offset);
      out += got;
      offset += static_cast<uint64_t>(got);
      left -= static_cast<uint64_t>(got);
    }
    return Status::ok();
  }

  Status readDeflate(size_t p, uint32_t z, uint32_t inPiece, uint32_t n, uint8_t* out) {
    if (z < nextSlice_)
      return makeError(ErrorCode::kInvalidArgument, info_.path,
                       ": compressed data is read in order: slice ", z, " requested after slice ",
                       nextSlice_, "; rewind() first");
    const ResolvedPiece& rp = pieces_[p];
    const uint64_t pieceBytes = uint64_t{rp.piece.slices} * info_.sliceBytes();
    if (!stream_ || streamPiece_ != p) {
      const std::string label = pieces_.size() == 1 && rp.piece.path == info_.path
                                    ? layout_.label
                                    : cat(layout_.label, " (", rp.piece.path, ")");
      VOXLINK_ASSIGN_OR_RETURN(stream_, InflateStream::open(rp.piece.path, rp.dataOffset, label));
      stream_->setExpectedSize(rp.piece.byteSkip + pieceBytes);
      VOXLINK_RETURN_IF_ERROR(stream_->skip(rp.piece.byteSkip));
      streamPiece_ = p;
    }
    const uint64_t want = rp.piece.byteSkip + uint64_t{inPiece} * info_.sliceBytes();
    if (stream_->position() < want)
      VOXLINK_RETURN_IF_ERROR(stream_->skip(want - stream_->position()));
    VOXLINK_RETURN_IF_ERROR(stream_->read(out, uint64_t{n} * info_.sliceBytes()));
    nextSlice_ = z + n;
    if (inPiece + n == rp.piece.slices) {
      // The whole piece is read: a stream with data left over means the header lies.
      VOXLINK_RETURN_IF_ERROR(stream_->expectEnd());
      stream_.reset();
    }
    return Status::ok();
  }

  std::vector<ResolvedPiece> pieces_;
  PieceLayout layout_;
  bool swap_ = false;
  int fd_ = -1;
  size_t fdPiece_ = SIZE_MAX;
  std::unique_ptr<InflateStream> stream_;
  size_t streamPiece_ = SIZE_MAX;
  uint32_t nextSlice_ = 0;
};

}  // namespace

Error unevenDataFiles(const std::string& path, std::string_view field, uint64_t files,
                      uint32_t depth) {
  return makeError(ErrorCode::kSizeMismatch, path, ": header field '", field, "': ", files,
                   " files cannot each hold whole z slices of ", depth);
}

Status addDataFilePieces(const DataPiece& base, const std::vector<std::string>& files,
                         uint32_t depth, const std::string& path, std::string_view field,
                         PieceLayout& layout) {
  if (files.empty() || depth % files.size() != 0)
    return unevenDataFiles(path, field, files.size(), depth);
  for (const std::string& file : files) {
    DataPiece piece = base;
    piece.path = file;
    piece.slices = static_cast<uint32_t>(depth / files.size());
    layout.pieces.push_back(piece);
  }
  return Status::ok();
}

Result<std::unique_ptr<VolumeSource>> openDataPieces(VolumeInfo info, PieceLayout layout) {
  if (layout.pieces.empty())
    return makeError(ErrorCode::kCorrupt, layout.label, ": no data file named");
  uint64_t slices = 0;
  for (const DataPiece& p : layout.pieces) slices += p.slices;
  if (slices != info.dims[2])
    return makeError(ErrorCode::kSizeMismatch, layout.label, ": ", layout.pieces.size(),
                     " data files hold ", slices, " slices, the header says ", info.dims[2]);

  for (const DataPiece& p : layout.pieces)
    if (std::find(info.files.begin(), info.files.end(), p.path) == info.files.end())
      info.files.push_back(p.path);

  std::vector<ResolvedPiece> resolved;
  uint32_t first = 0;
  for (const DataPiece& p : layout.pieces) {
    std::error_code ec;
    const auto size = fs::file_size(p.path, ec);
    if (ec) {
      if (!fs::exists(p.path, ec)) return missingFile(layout.label, p.path);
      VOXLINK_RETURN_IF_ERROR(base::requireRegularFile(p.path, "data file"));  // a FIFO...
      return makeError(ErrorCode::kIo, layout.label, ": cannot read ", p.path);
    }
    ResolvedPiece rp{p, p.startOffset, first};
    if (p.lineSkip > 0) {
      VOXLINK_ASSIGN_OR_RETURN(rp.dataOffset,
                               skipLines(p.path, p.startOffset, p.lineSkip, layout.label));
    }
    const uint64_t needed = uint64_t{p.slices} * info.sliceBytes();
    if (layout.encoding == PieceEncoding::kRaw) {
      if (p.dataAtEnd) {
        if (size < needed + rp.dataOffset)
          return makeError(ErrorCode::kTruncated, layout.label, ": ", p.path, " has ", size,
                           " bytes, fewer than the ", needed, " bytes of data it should end with");
        rp.dataOffset = size - needed;
      } else {
        rp.dataOffset += p.byteSkip;
        const uint64_t available = size > rp.dataOffset ? size - rp.dataOffset : 0;
        // Attached data is already named by the label; a data file is named here.
        const std::string file = p.path == info.path ? std::string() : p.path + ": ";
        const std::string shape =
            cat(info.dims[0], "x", info.dims[1], "x", p.slices, " ", scalarName(info.type));
        if (available < needed)
          return makeError(ErrorCode::kTruncated, layout.label, ": ", file, shape, " needs ",
                           needed, " bytes after byte ", rp.dataOffset, ", the file holds only ",
                           available);
        if (layout.exactSize && available != needed)
          return makeError(ErrorCode::kSizeMismatch, layout.label, ": ", file, shape, " needs ",
                           needed, " bytes after byte ", rp.dataOffset, ", the file holds ",
                           available, " (header sizes or type wrong?)");
      }
    } else if (p.dataAtEnd) {
      return makeError(ErrorCode::kUnsupported, layout.label,
                       ": byte skip -1 (data at the end) is only defined for raw data");
    }
    resolved.push_back(rp);
    first += p.slices;
  }

  // One raw file: map it, so converters get the zero-copy path.
  if (layout.encoding == PieceEncoding::kRaw && resolved.size() == 1)
    return openRawData(resolved[0].piece.path, std::move(info), layout.endian,
                       resolved[0].dataOffset, false);
  return std::unique_ptr<VolumeSource>(
      new PieceSource(std::move(info), std::move(resolved), std::move(layout)));
}

}  // namespace voxlink::sources
