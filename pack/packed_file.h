// SPDX-License-Identifier: BSD-3-Clause
// Packed VoxLink files: the same file with every section compressed losslessly, for storage and
// transfer (docs/format.md, "Packed files"). A packed file unpacks to the exact bytes of the
// file it was made from; pack::openFile() (pack/open_file.h) unpacks one in memory, so every
// command reads both.
//
//   header (256, magic "VOXLINKZ") | packed sections | PACK | section table
//
// The packed table lists each compressed payload with a CRC-32C of the bytes as written; PACK
// keeps the original section table (with the original checksums, checked again after
// decoding) and how each section was encoded.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/progress.h"
#include "format/voxlink_file.h"
#include "pack/detail/section_codec.h"

namespace voxlink::pack {

using format::SectionId;
using format::VoxLinkFile;

inline constexpr char kPackedMagic[8] = {'V', 'O', 'X', 'L', 'I', 'N', 'K', 'Z'};
inline constexpr uint32_t kPackVersion = 1;

bool isPackedFile(std::span<const uint8_t> bytes);

struct PackOptions {
  int level = 1;         // zstd level: 1 is fast; higher levels gain little on these sections
  unsigned threads = 0;  // 0: every core
  // GRAD as the difference to its prediction from the values (GradientPrediction::kPortable:
  // about 7x smaller than the codes, but the prediction costs most of the packing and
  // unpacking time); false: delta-coded like the other sections.
  bool predictGradients = true;
  // May be empty: hears the fraction done after each section (weighted by its bytes) and once
  // the file is written.
  ProgressCallback progress;
};

struct PackedSection {
  SectionId id;
  SectionCodec codec;
  uint64_t rawBytes = 0;
  uint64_t packedBytes = 0;
};

struct PackReport {
  uint64_t inputBytes = 0;
  uint64_t outputBytes = 0;
  double packSeconds = 0;     // predicting, compressing, checking and writing
  double predictSeconds = 0;  // of which predicting the gradients
  std::vector<PackedSection> sections;
};

// Packs `file` (which the caller has validated) into `path`: a temporary beside it, renamed into
// place only after every payload was decoded again and matched what was encoded (and every
// derived section matched the file's).
Result<PackReport> packFile(const VoxLinkFile& file, const std::string& path,
                            const PackOptions& options = {});

// The file a packed one was made from, in memory. `name` is used in messages; the unpacked file
// may not exceed `maxBytes`. `progress` (may be empty) hears the fraction done after each
// section is decoded (weighted by its bytes) and once the checksums are checked.
Result<VoxLinkFile> unpackFile(std::span<const uint8_t> packed, const std::string& name,
                               uint64_t maxBytes, unsigned threads = 0,
                               const ProgressCallback& progress = {});

}  // namespace voxlink::pack
