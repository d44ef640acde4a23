// SPDX-License-Identifier: BSD-3-Clause
// The data part of header-described volumes (NRRD, MetaImage, NIfTI, Voreen): one or more
// files, each holding a run of whole z slices, raw or deflate-compressed. A single raw file is
// memory-mapped (zero-copy map()); several raw files are read with pread (random access);
// compressed data is decoded as a sequential stream.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sources/volume_source.h"

namespace voxlink::sources {

enum class PieceEncoding { kRaw, kDeflate };  // kDeflate: zlib or gzip framing

struct DataPiece {
  std::string path;
  uint64_t startOffset = 0;  // bytes before everything else (an attached header)
  uint64_t lineSkip = 0;     // then this many text lines of the file are skipped (NRRD line skip)
  uint64_t byteSkip = 0;     // raw: file bytes after the lines; deflate: decoded bytes
  bool dataAtEnd = false;    // raw only: the data is the last bytes of the file (byte skip -1)
  uint32_t slices = 0;       // z slices this piece holds
};

struct PieceLayout {
  std::vector<DataPiece> pieces;
  PieceEncoding encoding = PieceEncoding::kRaw;
  Endian endian = Endian::kLittle;
  // Raw files must hold exactly the described bytes (after the skips); a longer file almost
  // always means the header lies about sizes or type.
  bool exactSize = true;
  // Starts messages about the data ("foot.nrrd: data").
  std::string label;
};

// The error of a header whose `files` data files (field `field`) cannot each hold whole z slices
// of `depth`.
Error unevenDataFiles(const std::string& path, std::string_view field, uint64_t files,
                      uint32_t depth);

// Adds one piece per data file, each a copy of `base` holding an equal share of the `depth` z
// slices; unevenDataFiles when they do not divide evenly. `path` and `field` name the header
// and its file-list field (MetaImage ElementDataFile, NRRD data file) in the message.
Status addDataFilePieces(const DataPiece& base, const std::vector<std::string>& files,
                         uint32_t depth, const std::string& path, std::string_view field,
                         PieceLayout& layout);

// Checks that every piece exists and (raw) has the right size, then returns the source.
// `info` must be complete (dims, type, spacing, path, format).
Result<std::unique_ptr<VolumeSource>> openDataPieces(VolumeInfo info, PieceLayout layout);

}  // namespace voxlink::sources
