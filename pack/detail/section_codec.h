// SPDX-License-Identifier: BSD-3-Clause
// Lossless encodings of one section's payload for packed files (pack/packed_file.h). A
// payload is cut into chunks of kPackChunkBytes that are transformed and compressed with zstd
// independently, so both directions run on every core:
//
//   payload = u32 chunkCount | u32 0 | u64 frameEnd[chunkCount] | zstd frames | zero padding
//
// frameEnd[c] is where chunk c's frame ends, counted from the first frame. The transforms make
// the bytes zstd sees more alike (docs/format.md, "Packed files").
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "base/error.h"

namespace voxlink::pack {

enum class SectionCodec : uint32_t {
  kStored = 0,                    // the bytes as they are, no chunk table
  kZstd = 1,                      // zstd of each chunk
  kDeltaZstd = 2,                 // byte planes of the elements, each plane delta-coded, then zstd
  kGradientResidual = 3,          // GRAD minus its float64 prediction (GradientPrediction::kExact,
                                  // pack/detail/gradient_predictor.h): byte planes, then zstd
  kGradientResidualPortable = 4,  // GRAD minus its float prediction (kPortable), the same way
  kDerived = 5,  // no payload: ROWS and BVOX follow from MASK (format/derived_sections.h)
};
bool isKnownSectionCodec(uint32_t raw);
// Codecs whose payload is GRAD minus a prediction.
bool isGradientResidual(SectionCodec codec);

inline constexpr uint64_t kPackChunkBytes = uint64_t{4} << 20;

// What the residual codecs subtract: the first `count` u16 of the section minus their
// predictions (the rest is taken as it is). fill(first, out) writes the predictions of entries
// [first, first + out.size()); it is called for each chunk as it is encoded, from every worker.
struct CodePrediction {
  uint64_t count = 0;
  std::function<void(uint64_t first, std::span<uint16_t> out)> fill;
};

// Encodes `raw`, a section of `elementBytes`-sized elements (byte planes of 1, 2 or 4 bytes;
// larger records as 4-byte words), at zstd `level`; the residual codecs need `prediction`.
// Every chunk is decoded again right after it was compressed and must give back its bytes: a
// payload that does not decode to what was meant is never returned.
Result<std::vector<uint8_t>> encodeSection(std::span<const uint8_t> raw, uint32_t elementBytes,
                                           SectionCodec codec, int level, unsigned threads,
                                           const CodePrediction& prediction = {});

// Decodes `packed` into `out`, whose size is the original payload size. Every chunk must
// decode to exactly its share; `where` names the section in errors. Residual codecs give the
// residual: the caller adds the prediction.
Status decodeSection(std::span<const uint8_t> packed, uint32_t elementBytes, SectionCodec codec,
                     std::span<uint8_t> out, const std::string& where, unsigned threads);

}  // namespace voxlink::pack
