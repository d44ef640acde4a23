// SPDX-License-Identifier: BSD-3-Clause
#include "pack/detail/section_codec.h"

#include <zstd.h>

#ifdef __SSSE3__
#include <tmmintrin.h>
#endif

#include <algorithm>
#include <cstring>
#include <memory>

#include "base/parallel_for.h"
#include "format/layout.h"

namespace voxlink::pack {

using format::alignUp;

namespace {

constexpr uint64_t kChunkTableHead = 8;  // chunkCount, reserved

// Byte planes of an element: 1, 2 or 4 (records of 32 or 64 bytes are split as u32 words).
uint32_t planesOf(uint32_t elementBytes) {
  return elementBytes == 1 || elementBytes == 2 ? elementBytes : 4;
}

uint64_t chunkCountOf(uint64_t bytes) { return (bytes + kPackChunkBytes - 1) / kPackChunkBytes; }

// Byte j of element i goes to plane j; with `delta`, each plane then holds differences of
// neighbouring bytes (mod 256), which are near 0 where values change slowly. With `predicted`
// (u16 elements only), element i is first replaced by its difference to predicted[i] for the
// elements that have one. Bytes after the last whole element are kept as they are.
void toPlanes(const uint8_t* in, uint64_t bytes, uint32_t e, bool delta, uint8_t* out,
              std::span<const uint16_t> predicted = {}) {
  const uint64_t count = bytes / e;
  if (!predicted.empty()) {  // e == 2
    const uint64_t n = std::min<uint64_t>(count, predicted.size());
    uint8_t* lo = out;
    uint8_t* hi = out + count;
    for (uint64_t i = 0; i < count; ++i) {
      uint16_t code;
      std::memcpy(&code, in + 2 * i, 2);
      if (i < n) code = static_cast<uint16_t>(code - predicted[i]);
      lo[i] = static_cast<uint8_t>(code);
      hi[i] = static_cast<uint8_t>(code >> 8);
    }
  } else {
    for (uint32_t j = 0; j < e; ++j) {
      uint8_t* plane = out + j * count;
      uint8_t previous = 0;
      for (uint64_t i = 0; i < count; ++i) {
        const uint8_t b = in[i * e + j];
        plane[i] = delta ? static_cast<uint8_t>(b - previous) : b;
        previous = b;
      }
    }
  }
  std::memcpy(out + count * e, in + count * e, bytes - count * e);
}

// out[i] = in[0] + ... + in[i] (mod 256): a plane of single bytes back from its differences,
// sixteen bytes at a time (each vector's running sums in four shifted adds, plus the last sum
// before it). The values of a volume are such a plane; one byte at a time, undoing the
// differences was most of decoding them.
void prefixSums(const uint8_t* in, uint64_t count, uint8_t* out) {
  uint64_t i = 0;
  uint8_t previous = 0;
#ifdef __SSSE3__
  __m128i carry = _mm_setzero_si128();  // the last sum, in every lane
  const __m128i lastLane = _mm_set1_epi8(15);
  for (; i + 16 <= count; i += 16) {
    __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + i));
    x = _mm_add_epi8(x, _mm_slli_si128(x, 1));
    x = _mm_add_epi8(x, _mm_slli_si128(x, 2));
    x = _mm_add_epi8(x, _mm_slli_si128(x, 4));
    x = _mm_add_epi8(x, _mm_slli_si128(x, 8));
    x = _mm_add_epi8(x, carry);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), x);
    carry = _mm_shuffle_epi8(x, lastLane);
  }
  if (i > 0) previous = out[i - 1];
#endif
  for (; i < count; ++i) out[i] = previous = static_cast<uint8_t>(in[i] + previous);
}

void fromPlanes(const uint8_t* in, uint64_t bytes, uint32_t e, bool delta, uint8_t* out) {
  const uint64_t count = bytes / e;
  if (e == 1 && delta) {
    prefixSums(in, count, out);
  } else if (e == 2 && !delta) {
    for (uint64_t i = 0; i < count; ++i) {
      out[2 * i] = in[i];
      out[2 * i + 1] = in[count + i];
    }
  } else {
    for (uint32_t j = 0; j < e; ++j) {
      const uint8_t* plane = in + j * count;
      uint8_t previous = 0;
      for (uint64_t i = 0; i < count; ++i) {
        const uint8_t b = delta ? static_cast<uint8_t>(plane[i] + previous) : plane[i];
        out[i * e + j] = b;
        previous = b;
      }
    }
  }
  std::memcpy(out + count * e, in + count * e, bytes - count * e);
}

// Scratch buffers of a worker thread, kept between chunks: fresh ones would cost a page fault
// per 4 KiB.
std::vector<uint8_t>& scratch(int which) {
  thread_local std::vector<uint8_t> buffers[4];
  return buffers[which];
}

// Adds predicted[i] to the i-th u16 of `codes`, wrapping around: a residual back to the codes.
// `codes` must hold at least predicted.size() entries.
void addPredictedCodes(std::span<uint8_t> codes, std::span<const uint16_t> predicted) {
  for (uint64_t i = 0; i < predicted.size(); ++i) {
    uint16_t code;
    std::memcpy(&code, codes.data() + 2 * i, 2);
    code = static_cast<uint16_t>(code + predicted[i]);
    std::memcpy(codes.data() + 2 * i, &code, 2);
  }
}

bool transforms(SectionCodec codec) {
  return codec == SectionCodec::kDeltaZstd || isGradientResidual(codec);
}

}  // namespace

bool isKnownSectionCodec(uint32_t raw) { return raw <= uint32_t(SectionCodec::kDerived); }

bool isGradientResidual(SectionCodec codec) {
  return codec == SectionCodec::kGradientResidual ||
         codec == SectionCodec::kGradientResidualPortable;
}

Result<std::vector<uint8_t>> encodeSection(std::span<const uint8_t> raw, uint32_t elementBytes,
                                           SectionCodec codec, int level, unsigned threads,
                                           const CodePrediction& prediction) {
  if (codec == SectionCodec::kStored) return std::vector<uint8_t>(raw.begin(), raw.end());
  if (codec == SectionCodec::kDerived)
    return makeError(ErrorCode::kInvalidArgument, "a derived section has no payload to encode");
  const bool residual = isGradientResidual(codec);
  if (residual && (elementBytes != 2 || prediction.count * 2 > raw.size() || !prediction.fill))
    return makeError(ErrorCode::kInvalidArgument, "gradient residual: ", prediction.count,
                     " predicted codes for ", raw.size(), " bytes of ", elementBytes,
                     "-byte elements");
  const uint64_t chunks = chunkCountOf(raw.size());
  const uint32_t planes = planesOf(elementBytes);
  const bool delta = codec == SectionCodec::kDeltaZstd;
  std::vector<std::vector<uint8_t>> frames(chunks);
  std::vector<std::string> errors(chunks);
  parallelFor(chunks, threads, [&](uint64_t c) {
    const uint64_t begin = c * kPackChunkBytes;
    const uint64_t bytes = std::min<uint64_t>(kPackChunkBytes, raw.size() - begin);
    const uint8_t* chunk = raw.data() + begin;
    const uint8_t* src = chunk;
    std::vector<uint8_t>& transformed = scratch(0);
    std::span<const uint16_t> chunkPredicted;
    if (residual && begin / 2 < prediction.count) {
      thread_local std::vector<uint16_t> predicted;
      predicted.resize(std::min<uint64_t>(bytes / 2, prediction.count - begin / 2));
      prediction.fill(begin / 2, predicted);
      chunkPredicted = predicted;
    }
    if (transforms(codec)) {
      transformed.resize(bytes);
      toPlanes(chunk, bytes, planes, delta, transformed.data(), chunkPredicted);
      src = transformed.data();
    }
    // Compressed into reused scratch, then copied out at its size: a fresh bound-sized frame
    // per chunk would be zeroed and faulted in, about as many bytes as the section itself.
    std::vector<uint8_t>& bound = scratch(3);
    bound.resize(ZSTD_compressBound(bytes));
    // One context per thread, reused: creating one costs about a millisecond.
    thread_local std::unique_ptr<ZSTD_CCtx, size_t (*)(ZSTD_CCtx*)> context(ZSTD_createCCtx(),
                                                                            ZSTD_freeCCtx);
    ZSTD_CCtx_reset(context.get(), ZSTD_reset_session_and_parameters);
    ZSTD_CCtx_setParameter(context.get(), ZSTD_c_compressionLevel, level);
    if (level == 1) {
      // Level 1 with a smaller hash table and a longer minimum match, faster on these
      // sections and smaller in total (zstd -b on the 1024^3 foot's: GRAD residual 631
      // against 574 MB/s and 2.9 % smaller, values 486 against 380 MB/s and 0.9 % larger,
      // masks 435 against 395 MB/s and 0.7 % smaller).
      ZSTD_CCtx_setParameter(context.get(), ZSTD_c_strategy, ZSTD_fast);
      ZSTD_CCtx_setParameter(context.get(), ZSTD_c_windowLog, 18);
      ZSTD_CCtx_setParameter(context.get(), ZSTD_c_hashLog, 10);
      ZSTD_CCtx_setParameter(context.get(), ZSTD_c_minMatch, 7);
      ZSTD_CCtx_setParameter(context.get(), ZSTD_c_searchLog, 1);
    }
    const size_t written = ZSTD_compress2(context.get(), bound.data(), bound.size(), src, bytes);
    if (ZSTD_isError(written)) {
      errors[c] = std::string("zstd: ") + ZSTD_getErrorName(written);
      return;
    }
    std::vector<uint8_t>& frame = frames[c];
    frame.assign(bound.begin(), bound.begin() + static_cast<ptrdiff_t>(written));
    // The check, while the chunk is still in the cache: decode as a reader would.
    thread_local std::unique_ptr<ZSTD_DCtx, size_t (*)(ZSTD_DCtx*)> checker(ZSTD_createDCtx(),
                                                                            ZSTD_freeDCtx);
    std::vector<uint8_t>& decoded = scratch(1);
    decoded.resize(bytes);
    const size_t got =
        ZSTD_decompressDCtx(checker.get(), decoded.data(), bytes, frame.data(), frame.size());
    // (and the frame must declare its size, which readers require)
    bool same = !ZSTD_isError(got) && got == bytes &&
                ZSTD_getFrameContentSize(frame.data(), frame.size()) == bytes;
    if (same && transforms(codec)) {
      std::vector<uint8_t>& restored = scratch(2);
      restored.resize(bytes);
      fromPlanes(decoded.data(), bytes, planes, delta, restored.data());
      addPredictedCodes(restored, chunkPredicted);
      same = std::memcmp(restored.data(), chunk, bytes) == 0;
    } else if (same) {
      same = std::memcmp(decoded.data(), chunk, bytes) == 0;
    }
    if (!same)
      errors[c] = "packing check: chunk " + std::to_string(c) + " does not decode to its bytes";
  });
  for (const std::string& e : errors)
    if (!e.empty())
      return makeError(e.starts_with("zstd") ? ErrorCode::kIo : ErrorCode::kCorrupt, e);
  uint64_t total = kChunkTableHead + 8 * chunks;
  for (const auto& f : frames) total += f.size();
  std::vector<uint8_t> out(alignUp(total, 4), 0);
  const uint32_t head[2] = {static_cast<uint32_t>(chunks), 0};
  std::memcpy(out.data(), head, sizeof head);
  uint64_t at = kChunkTableHead + 8 * chunks, end = 0;
  for (uint64_t c = 0; c < chunks; ++c) {
    std::memcpy(out.data() + at, frames[c].data(), frames[c].size());
    at += frames[c].size();
    end += frames[c].size();
    std::memcpy(out.data() + kChunkTableHead + 8 * c, &end, 8);
  }
  return out;
}

Status decodeSection(std::span<const uint8_t> packed, uint32_t elementBytes, SectionCodec codec,
                     std::span<uint8_t> out, const std::string& where, unsigned threads) {
  if (codec == SectionCodec::kDerived)
    return makeError(ErrorCode::kInvalidArgument, where, ": a derived section has no payload");
  if (codec == SectionCodec::kStored) {
    if (packed.size() != out.size())
      return makeError(ErrorCode::kSizeMismatch, where, ": stored payload has ", packed.size(),
                       " bytes, expected ", out.size());
    std::memcpy(out.data(), packed.data(), out.size());
    return Status::ok();
  }
  const uint64_t chunks = chunkCountOf(out.size());
  uint32_t head[2];
  if (packed.size() < sizeof head)
    return makeError(ErrorCode::kTruncated, where, ": payload of ", packed.size(),
                     " bytes has no chunk table");
  std::memcpy(head, packed.data(), sizeof head);
  if (head[0] != chunks || head[1] != 0)
    return makeError(ErrorCode::kCorrupt, where, ": chunkCount ", head[0], " (expected ", chunks,
                     " for ", out.size(), " bytes)");
  const uint64_t framesAt = kChunkTableHead + 8 * chunks;
  if (packed.size() < framesAt)
    return makeError(ErrorCode::kTruncated, where, ": chunk table runs past the payload");
  std::vector<uint64_t> ends(chunks);
  if (chunks > 0) std::memcpy(ends.data(), packed.data() + kChunkTableHead, 8 * chunks);
  uint64_t previous = 0;
  for (uint64_t c = 0; c < chunks; ++c) {
    if (ends[c] < previous || ends[c] > packed.size() - framesAt)
      return makeError(ErrorCode::kCorrupt, where, ": frameEnd[", c, "] = ", ends[c],
                       " is out of order or past the payload");
    previous = ends[c];
  }
  std::vector<std::string> errors(chunks);
  parallelFor(chunks, threads, [&](uint64_t c) {
    const uint64_t begin = c * kPackChunkBytes;
    const uint64_t bytes = std::min<uint64_t>(kPackChunkBytes, out.size() - begin);
    const uint8_t* frame = packed.data() + framesAt + (c == 0 ? 0 : ends[c - 1]);
    const uint64_t frameBytes = ends[c] - (c == 0 ? 0 : ends[c - 1]);
    const unsigned long long declared = ZSTD_getFrameContentSize(frame, frameBytes);
    if (declared != bytes) {
      errors[c] = "chunk " + std::to_string(c) + ": frame declares " +
                  (declared == ZSTD_CONTENTSIZE_ERROR || declared == ZSTD_CONTENTSIZE_UNKNOWN
                       ? std::string("no valid size")
                       : std::to_string(declared) + " bytes") +
                  ", expected " + std::to_string(bytes);
      return;
    }
    std::vector<uint8_t>& planes = scratch(0);
    uint8_t* dst = out.data() + begin;
    if (transforms(codec)) {
      planes.resize(bytes);
      dst = planes.data();
    }
    thread_local std::unique_ptr<ZSTD_DCtx, size_t (*)(ZSTD_DCtx*)> context(ZSTD_createDCtx(),
                                                                            ZSTD_freeDCtx);
    const size_t got = ZSTD_decompressDCtx(context.get(), dst, bytes, frame, frameBytes);
    if (ZSTD_isError(got) || got != bytes) {
      errors[c] = "chunk " + std::to_string(c) + ": " +
                  (ZSTD_isError(got) ? std::string(ZSTD_getErrorName(got)) : "short frame");
      return;
    }
    if (transforms(codec))
      fromPlanes(planes.data(), bytes, planesOf(elementBytes), codec == SectionCodec::kDeltaZstd,
                 out.data() + begin);
  });
  for (const std::string& e : errors)
    if (!e.empty()) return makeError(ErrorCode::kCorrupt, where, ": ", e);
  return Status::ok();
}

}  // namespace voxlink::pack
