// SPDX-License-Identifier: BSD-3-Clause
// Pass 2 of the converter: encodes the occupied bricks of a row of bricks (row starts, row
// masks, values, gradients) into the file's sections, templated on the source element type T
// and the keep rule (keep_rule.h). Jobs are rows of bricks as in pass 1 (brick_count_pass.h),
// so the output does not depend on slab size or thread count.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "convert/detail/encode_output.h"

#if defined(__SSE4_1__)
#include <immintrin.h>
#endif

#include "convert/detail/brick_count_pass.h"
#include "convert/detail/brick_gradients.h"
#include "convert/detail/slab_window.h"
#include "convert/detail/value_mapping.h"
#include "format/gradient_codec.h"
#include "format/layout.h"
#include "format/source_value.h"

namespace voxlink::convert {

// Keep flags of every cell of a row of bricks (n slices x n rows x the whole width), x fastest,
// into flags[(z - z0) * n * nx + (y - y0) * nx + x].
// Long contiguous loops: they vectorize and stream the row's source data into cache in order,
// so the per-brick work that follows reads from L2 instead of striding through slices.
// Only x in [x0, x1) is filled: the span of the row's occupied bricks.
template <class T, class Keep>
void rowKeepFlags(const BrickRow& row, uint32_t x0, uint32_t x1, const Keep keep,
                  uint8_t* __restrict flags) {
  const SlabWindow& window = row.window;
  const uint32_t n = row.grid.n, nx = row.grid.dims[0];
  const uint32_t z0 = row.bz * n, z1 = std::min(row.grid.dims[2], z0 + n);
  const uint32_t y0 = row.by * n, y1 = std::min(row.grid.dims[1], y0 + n);
  for (uint32_t z = z0; z < z1; ++z) {
    const T* slice = reinterpret_cast<const T*>(window.slice(z));
    const uint8_t* activeSlice = window.active(z);
    for (uint32_t y = y0; y < y1; ++y) {
      const T* __restrict p = slice + uint64_t{y} * nx;
      uint8_t* __restrict f = flags + (size_t{z - z0} * n + (y - y0)) * nx;
      for (uint32_t x = x0; x < x1; ++x) f[x] = keep(p[x]) ? 1 : 0;
      if (activeSlice) {  // a source with inactive voxels (OpenVDB): those are never kept
        const uint8_t* __restrict active = activeSlice + uint64_t{y} * nx;
        for (uint32_t x = x0; x < x1; ++x) f[x] &= active[x];
      }
    }
  }
}

// Pass 1's numbers for one row of bricks: its kept-voxel counts per brick, the index of its
// first occupied brick, and every occupied brick's first voxel in the file.
struct RowCensus {
  const uint16_t* counts;
  uint64_t firstOccupied;
  const uint32_t* voxelBase;
};

// What the encoders share for every brick of one row of bricks.
struct RowEncoding {
  const uint32_t* dims;  // volume extent along x, y, z
  format::AxisFrame frame;
  uint32_t n;
  const ValueMapping& mapping;
  bool lossless;       // stored = raw - integer offset (u8/u16 from an integer source)
  const double* half;  // 0.5 / spacing: central differences
  const double* full;  // 1 / spacing: one-sided differences at the volume border
};

// One occupied brick to encode: its cells, the dense per-cell arrays of an interior brick, and
// its place in the output sections.
template <class T>
struct BrickEncoding {
  BrickCells<T> cells;
  uint32_t origin[3];     // first cell, volume coordinates
  const float* dense[3];  // DenseBrick gradients (interior bricks), else nulls
  const T* center;        // DenseBrick values
  uint32_t expected;      // kept voxels pass 1 counted: more means the source changed
  uint16_t* rows;         // row starts, n*n
  uint32_t* mask;         // row masks
  uint8_t* values;        // stored values, little-endian
  float* g[3];            // gradients of the kept voxels in list order, for the batch encoder
};

// Encodes one occupied brick: its row starts, row masks, values and gradients. `Interior`
// says the brick and a one-voxel margin lie inside the volume, so no border tests are needed.
// Returns the kept voxels written, or UINT32_MAX when there are more than job.expected.
template <class T, bool Interior>
uint32_t encodeBrick(const RowEncoding& shared, const BrickEncoding<T>& job, EncodeStats& stats) {
  const T* brick = job.cells.source;
  const int64_t* stride = job.cells.stride;
  const uint8_t* flags = job.cells.flags;
  const size_t* flagStride = job.cells.flagStride;
  const uint32_t* origin = job.origin;
  const float* const* dense = job.dense;
  const uint32_t expected = job.expected;
  uint16_t* rows = job.rows;
  uint32_t* mask = job.mask;
  uint8_t* values = job.values;
  float* gx = job.g[0];
  float* gy = job.g[1];
  float* gz = job.g[2];
  const uint32_t* dims = shared.dims;
  const format::AxisFrame frame = shared.frame;
  const uint32_t n = shared.n;
  const ValueMapping& mapping = shared.mapping;
  const bool lossless = shared.lossless;
  const double* half = shared.half;
  const double* full = shared.full;
  const int su = frame.u, sv = frame.v, sw = frame.w;
  const uint32_t extentU = Interior ? n : std::min(n, dims[su] - origin[su]);
  const uint32_t extentV = Interior ? n : std::min(n, dims[sv] - origin[sv]);
  const uint32_t extentW = Interior ? n : std::min(n, dims[sw] - origin[sw]);
  const size_t valueSize = storedSize(mapping.type);
  const int64_t intOffset = static_cast<int64_t>(mapping.offset);
  T rawMin = std::numeric_limits<T>::max(), rawMax = std::numeric_limits<T>::lowest();
  uint32_t count = 0;
  for (uint32_t row = 0; row < n * n; ++row) {
    rows[row] = static_cast<uint16_t>(count);
    const uint32_t u = row % n, v = row / n;
    if (!Interior && (u >= extentU || v >= extentV)) continue;
    const T* line = brick + u * stride[su] + v * stride[sv];
    // The row's occupancy bits, branch-free; then visit the set bits.
    uint32_t bits = 0;
    {  // from the row's keep flags: strides 1, nx, n*nx (flags points at this brick's corner)
      const uint8_t* f = flags + u * flagStride[su] + v * flagStride[sv];
      for (uint32_t d = 0; d < extentW; ++d) bits |= uint32_t{f[d * flagStride[sw]]} << d;
    }
    if (bits == 0) continue;
    if (count + static_cast<uint32_t>(std::popcount(bits)) > expected) return UINT32_MAX;
    const uint32_t bit0 = row * n;
    mask[bit0 >> 5] |= bits << (bit0 & 31);
    while (bits) {
      const uint32_t d = static_cast<uint32_t>(std::countr_zero(bits));
      bits &= bits - 1;
      const T* cell = line + d * stride[sw];
      const T raw = *cell;
      // Value.
      uint32_t stored;
      if (lossless) {
        stored = static_cast<uint32_t>(static_cast<int64_t>(raw) - intOffset);
        rawMin = std::min(rawMin, raw);
        rawMax = std::max(rawMax, raw);
      } else {
        const double exact = static_cast<double>(raw);
        stored = mapping.encode(exact);
        const double decoded = mapping.decode(stored);
        // The error an export really gives back: rounded and clamped to the source's type.
        const double err = std::abs(asSourceValueOf<T>(decoded) - exact);
        stats.maxAbsError = std::max(stats.maxAbsError, err);
        if (exact != 0) stats.maxRelError = std::max(stats.maxRelError, err / std::abs(exact));
        stats.valueMin = std::min(stats.valueMin, decoded);
        stats.valueMax = std::max(stats.valueMax, decoded);
      }
      std::memcpy(values + count * valueSize, &stored, valueSize);  // little-endian host
      // Gradient: central differences, one-sided at the volume border.
      if (dense[0]) {  // computed for the whole brick already
        uint32_t local[3];
        local[su] = u;
        local[sv] = v;
        local[sw] = d;
        const size_t index = (size_t{local[2]} * n + local[1]) * n + local[0];
        gx[count] = dense[0][index];
        gy[count] = dense[1][index];
        gz[count] = dense[2][index];
        ++count;
        continue;
      }
      double grad[3];
      if constexpr (Interior) {
        for (int a = 0; a < 3; ++a)
          grad[a] = (static_cast<double>(cell[stride[a]]) - static_cast<double>(cell[-stride[a]])) *
                    half[a];
      } else {
        uint32_t p[3];
        p[su] = origin[su] + u;
        p[sv] = origin[sv] + v;
        p[sw] = origin[sw] + d;
        for (int a = 0; a < 3; ++a) {
          const bool hasLo = p[a] > 0, hasHi = p[a] + 1 < dims[a];
          const double lo = static_cast<double>(hasLo ? cell[-stride[a]] : raw);
          const double hi = static_cast<double>(hasHi ? cell[stride[a]] : raw);
          grad[a] = (hi - lo) * (hasLo && hasHi ? half[a] : full[a]);
        }
      }
      if constexpr (std::is_floating_point_v<T>) {  // keep huge differences inside float range
        const double big = std::max({std::abs(grad[0]), std::abs(grad[1]), std::abs(grad[2])});
        if (big > 1e30) grad[0] /= big, grad[1] /= big, grad[2] /= big;
      }
      gx[count] = static_cast<float>(grad[0]);
      gy[count] = static_cast<float>(grad[1]);
      gz[count] = static_cast<float>(grad[2]);
      ++count;
    }
  }
  if (lossless && count) {
    stats.valueMin = std::min(stats.valueMin, static_cast<double>(rawMin));
    stats.valueMax = std::max(stats.valueMax, static_cast<double>(rawMax));
  }
  return count;
}

// Byte k of entry b: the position of the k-th set bit of b (unused bytes 0).
inline constexpr auto kSetBitPositions = [] {
  std::array<uint64_t, 256> table{};
  for (uint32_t b = 0; b < 256; ++b)
    for (uint32_t bit = 0, k = 0; bit < 8; ++bit)
      if (b >> bit & 1) table[b] |= uint64_t{bit} << (8 * k++);
  return table;
}();

// The common case, kept tight: an interior brick (neighbours on every side, so gradients and
// values come from the dense per-brick arrays), a brick edge known at compile time, and a
// lossless stored type S that holds the source value minus an integer offset (u8/u16), or f32
// bit for bit. Branch-free: which cells are kept varies from row to row in no pattern a branch
// predictor can learn, so the kept cells' dense indices are compacted by always storing and
// advancing by the keep bit, then gathered in one loop. Returns the kept voxels written, or
// UINT32_MAX when there are more than `expected`. Like denseBrickGradientsN, the kernel keeps
// its __restrict parameters (brick_gradients.h says why); the dispatcher below takes the
// structs.
template <class T, class S, uint32_t N>
uint32_t encodeInteriorBrick(const format::AxisFrame frame, const uint8_t* flags,
                             const size_t flagStride[3], const float* const dense[3],
                             const T* __restrict center, int64_t offset, uint32_t expected,
                             uint16_t* __restrict rows, uint32_t* __restrict mask,
                             S* __restrict values, float* __restrict gx, float* __restrict gy,
                             float* __restrict gz, T& rawMin, T& rawMax) {
  constexpr uint32_t kDenseStride[3] = {1, N, N * N};
  const size_t fU = flagStride[frame.u], fV = flagStride[frame.v], fW = flagStride[frame.w];
  const uint32_t dU = kDenseStride[frame.u], dV = kDenseStride[frame.v], dW = kDenseStride[frame.w];
  // Every row's occupancy bits first. When rows run across x (u = x, the default z axis), the
  // flags of N rows are contiguous for each depth: an N*N-wide loop the compiler vectorizes.
  using Bits =
      std::conditional_t<(N <= 8), uint8_t, std::conditional_t<(N <= 16), uint16_t, uint32_t>>;
  Bits rowBits[N * N] = {};
  if (N % 8 == 0 && fU == 1) {
    // Eight 0/1 flag bytes per load, shifted by the depth within its group of eight: bit d % 8
    // of byte j in group d / 8 is the flag of row u = u0 + j at depth d, so each group holds
    // eight bits of eight rows at once.
    for (uint32_t v = 0; v < N; ++v) {
      for (uint32_t u0 = 0; u0 < N; u0 += 8) {
        uint64_t groups[N / 8 > 0 ? N / 8 : 1] = {};
        for (uint32_t d = 0; d < N; ++d) {
          uint64_t f;
          std::memcpy(&f, flags + u0 + v * fV + d * fW, 8);
          groups[d / 8] |= f << (d % 8);
        }
        for (uint32_t j = 0; j < 8; ++j) {
          uint32_t bits = 0;
          for (uint32_t g = 0; g < N / 8; ++g)
            bits |= static_cast<uint32_t>((groups[g] >> (8 * j)) & 0xFF) << (8 * g);
          rowBits[v * N + u0 + j] = static_cast<Bits>(bits);
        }
      }
    }
  } else if (fU == 1) {
    for (uint32_t d = 0; d < N; ++d)
      for (uint32_t v = 0; v < N; ++v) {
        const uint8_t* __restrict f = flags + v * fV + d * fW;
        Bits* __restrict b = rowBits + v * N;
        for (uint32_t u = 0; u < N; ++u) b[u] = static_cast<Bits>(b[u] | (Bits{f[u]} << d));
      }
  } else {
    for (uint32_t v = 0; v < N; ++v)
      for (uint32_t u = 0; u < N; ++u) {
        const uint8_t* f = flags + u * fU + v * fV;
        uint32_t bits = 0;
        for (uint32_t d = 0; d < N; ++d) bits |= uint32_t{f[d * fW]} << d;
        rowBits[v * N + u] = static_cast<Bits>(bits);
      }
  }
  using Index = uint16_t;      // cells of a brick: at most 32^3 = 32768
  Index index[N * N * N + 8];  // + 8: a row is stored 8 entries at a time
  uint32_t count = 0;
  for (uint32_t v = 0; v < N; ++v) {
    for (uint32_t u = 0; u < N; ++u) {
      const uint32_t row = v * N + u;
      rows[row] = static_cast<uint16_t>(count);
      const uint32_t bits = rowBits[row];
      mask[(row * N) >> 5] |= bits << ((row * N) & 31);
      const uint32_t base = u * dU + v * dV;
#if defined(__SSE4_1__)
      // Eight depths at a time: all 8 positions of a byte of the row's bits from a table, of
      // which only the first popcount count.
      for (uint32_t g = 0; g < (N + 7) / 8; ++g) {
        const uint32_t byte = (bits >> (8 * g)) & 0xFF;
        const __m128i positions = _mm_cvtepu8_epi16(
            _mm_loadl_epi64(reinterpret_cast<const __m128i*>(&kSetBitPositions[byte])));
        const __m128i cells =
            _mm_add_epi16(_mm_set1_epi16(static_cast<int16_t>(base + 8 * g * dW)),
                          _mm_mullo_epi16(positions, _mm_set1_epi16(static_cast<int16_t>(dW))));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(index + count), cells);
        count += static_cast<uint32_t>(std::popcount(byte));
      }
#else
      for (uint32_t d = 0; d < N; ++d) {
        index[count] = static_cast<Index>(base + d * dW);  // may be overwritten: count only
        count += (bits >> d) & 1;                          // advances past kept cells
      }
#endif
      if (count > expected) return UINT32_MAX;  // index[] holds N^3 entries: stop before overrun
    }
  }
  const float* __restrict d0 = dense[0];
  const float* __restrict d1 = dense[1];
  const float* __restrict d2 = dense[2];
  for (uint32_t j = 0; j < count; ++j) {
    const uint32_t i = index[j];
    gx[j] = d0[i];
    gy[j] = d1[i];
    gz[j] = d2[i];
    if constexpr (std::is_same_v<S, float>) {
      values[j] = center[i];
    } else {
      values[j] = static_cast<S>(static_cast<int64_t>(center[i]) - offset);
    }
  }
  // The range over the stored values (contiguous: this loop vectorizes); stored = raw - offset.
  S lo = values[0], hi = values[0];
  for (uint32_t j = 1; j < count; ++j) {
    lo = values[j] < lo ? values[j] : lo;
    hi = values[j] > hi ? values[j] : hi;
  }
  if (count > 0) {
    T rawLo, rawHi;
    if constexpr (std::is_same_v<S, float>) {
      rawLo = lo, rawHi = hi;
    } else {
      rawLo = static_cast<T>(static_cast<int64_t>(lo) + offset);
      rawHi = static_cast<T>(static_cast<int64_t>(hi) + offset);
    }
    rawMin = std::min(rawMin, rawLo);
    rawMax = std::max(rawMax, rawHi);
  }
  return count;
}

template <class T, class S>
uint32_t encodeInteriorBrick(const RowEncoding& shared, const BrickEncoding<T>& job, int64_t offset,
                             T& rawMin, T& rawMax) {
  S* values = reinterpret_cast<S*>(job.values);
  switch (shared.n) {
    case 4:
      return encodeInteriorBrick<T, S, 4>(
          shared.frame, job.cells.flags, job.cells.flagStride, job.dense, job.center, offset,
          job.expected, job.rows, job.mask, values, job.g[0], job.g[1], job.g[2], rawMin, rawMax);
    case 8:
      return encodeInteriorBrick<T, S, 8>(
          shared.frame, job.cells.flags, job.cells.flagStride, job.dense, job.center, offset,
          job.expected, job.rows, job.mask, values, job.g[0], job.g[1], job.g[2], rawMin, rawMax);
    case 16:
      return encodeInteriorBrick<T, S, 16>(
          shared.frame, job.cells.flags, job.cells.flagStride, job.dense, job.center, offset,
          job.expected, job.rows, job.mask, values, job.g[0], job.g[1], job.g[2], rawMin, rawMax);
    default:
      return encodeInteriorBrick<T, S, 32>(
          shared.frame, job.cells.flags, job.cells.flagStride, job.dense, job.center, offset,
          job.expected, job.rows, job.mask, values, job.g[0], job.g[1], job.g[2], rawMin, rawMax);
  }
}

template <class T, class Keep>
void encodeBrickRow(const BrickRow& brickRow, const Keep& keep, const ValueMapping& mapping,
                    const RowCensus& census, const SlabOutput& out, uint32_t errorStride,
                    EncodeStats& stats) {
  const SlabWindow& window = brickRow.window;
  const GridShape& g = brickRow.grid;
  const uint32_t bz = brickRow.bz, by = brickRow.by;
  const uint16_t* counts = census.counts;
  const uint32_t* voxelBase = census.voxelBase;
  const uint32_t n = g.n;
  const uint32_t maskWords = format::maskWordsPerBrick(n);
  const uint32_t dims[3] = {g.dims[0], g.dims[1], g.dims[2]};
  const size_t valueSize = storedSize(mapping.type);
  const bool lossless = mapping.errorBound == 0.0 && !std::is_floating_point_v<T> &&
                        (mapping.type == StoredType::kU8 || mapping.type == StoredType::kU16);
  // The window's slices are contiguous: element strides along x, y, z.
  const int64_t stride[3] = {1, int64_t{dims[0]}, int64_t{dims[0]} * dims[1]};
  const double half[3] = {0.5 / g.spacing[0], 0.5 / g.spacing[1], 0.5 / g.spacing[2]};
  const double full[3] = {1.0 / g.spacing[0], 1.0 / g.spacing[1], 1.0 / g.spacing[2]};
  thread_local struct {
    std::vector<float> gx, gy, gz;              // gradients of the brick's kept voxels
    std::vector<float> denseX, denseY, denseZ;  // gradients of every cell of an interior brick
    std::vector<T> denseV;                      // and its values
    std::vector<uint8_t> flags;                 // keep flags of the whole row of bricks
  } scratch;
  const size_t cells = uint64_t{n} * n * n;
  scratch.gx.resize(cells);
  scratch.gy.resize(cells);
  scratch.gz.resize(cells);
  constexpr bool kDense = !std::is_same_v<T, double>;
  // Keep flags of the row of bricks (n slices x n rows x nx), over its occupied span only:
  // sparse volumes have many empty rows and long empty runs.
  uint32_t bxFirst = 0, bxEnd = g.grid[0];
  while (bxFirst < bxEnd && counts[bxFirst] == 0) ++bxFirst;
  while (bxEnd > bxFirst && counts[bxEnd - 1] == 0) --bxEnd;
  if (bxFirst == bxEnd) return;
  scratch.flags.resize(size_t{n} * n * dims[0]);
  rowKeepFlags<T>(brickRow, bxFirst * n, std::min(dims[0], bxEnd * n), keep, scratch.flags.data());
  const size_t flagStride[3] = {1, dims[0], size_t{n} * dims[0]};
  if (kDense) {
    scratch.denseX.resize(cells);
    scratch.denseY.resize(cells);
    scratch.denseZ.resize(cells);
    scratch.denseV.resize(cells);
  }
  const float halfF[3] = {static_cast<float>(half[0]), static_cast<float>(half[1]),
                          static_cast<float>(half[2])};
  const RowEncoding rowEncoding{dims, g.frame, n, mapping, lossless, half, full};

  uint64_t k = census.firstOccupied;
  for (uint32_t bx = bxFirst; bx < bxEnd; ++bx) {
    if (counts[bx] == 0) continue;
    const uint64_t vbase = voxelBase[k];
    uint16_t* rows = out.rows + (k - out.k0) * n * n;
    uint32_t* mask = out.masks + (k - out.k0) * maskWords;
    uint8_t* values = out.values + (vbase - out.v0) * valueSize;
    uint16_t* grads = out.gradients + (vbase - out.v0);
    const uint32_t origin[3] = {bx * n, by * n, bz * n};
    const T* brick = reinterpret_cast<const T*>(window.slice(origin[2])) +
                     int64_t{origin[1]} * stride[1] + origin[0];
    bool interior = true;
    for (int a = 0; a < 3; ++a) interior &= origin[a] > 0 && origin[a] + n < dims[a];
    BrickEncoding<T> job{{brick, stride, scratch.flags.data() + origin[0], flagStride},
                         {origin[0], origin[1], origin[2]},
                         {nullptr, nullptr, nullptr},
                         scratch.denseV.data(),
                         counts[bx],
                         rows,
                         mask,
                         values,
                         {scratch.gx.data(), scratch.gy.data(), scratch.gz.data()}};
    if (kDense && interior) {  // only x lines with a kept cell: the others are never read
      denseBrickGradients(
          job.cells, n, halfF,
          DenseBrick<T>{{scratch.denseX.data(), scratch.denseY.data(), scratch.denseZ.data()},
                        scratch.denseV.data()});
      job.dense[0] = scratch.denseX.data();
      job.dense[1] = scratch.denseY.data();
      job.dense[2] = scratch.denseZ.data();
    }
    // The tight path when it applies (interior, dense gradients, lossless u8/u16/f32 values).
    uint32_t count = UINT32_MAX;
    const bool f32Copy = std::is_same_v<T, float> && mapping.type == StoredType::kF32 &&
                         mapping.scale == 1.0 && mapping.offset == 0.0;
    if (kDense && interior && (lossless || f32Copy)) {
      T rawMin = std::numeric_limits<T>::max(), rawMax = std::numeric_limits<T>::lowest();
      const int64_t offset = static_cast<int64_t>(mapping.offset);
      if (mapping.type == StoredType::kU8)
        count = encodeInteriorBrick<T, uint8_t>(rowEncoding, job, offset, rawMin, rawMax);
      else if (mapping.type == StoredType::kU16)
        count = encodeInteriorBrick<T, uint16_t>(rowEncoding, job, offset, rawMin, rawMax);
      else if constexpr (std::is_same_v<T, float>)
        count = encodeInteriorBrick<T, float>(rowEncoding, job, offset, rawMin, rawMax);
      if (count != UINT32_MAX && count > 0) {
        stats.valueMin = std::min(stats.valueMin, static_cast<double>(rawMin));
        stats.valueMax = std::max(stats.valueMax, static_cast<double>(rawMax));
      }
    } else {
      count = interior ? encodeBrick<T, true>(rowEncoding, job, stats)
                       : encodeBrick<T, false>(rowEncoding, job, stats);
    }
    if (count != counts[bx]) {
      stats.countMismatch = true;
      return;
    }
    format::encodeGradients(scratch.gx.data(), scratch.gy.data(), scratch.gz.data(), grads, count);
    uint32_t zeros = 0;  // a 32-bit sum per brick vectorizes without widening to 64 bits
    for (uint32_t i = 0; i < count; ++i) zeros += grads[i] == format::kZeroGradient;
    stats.zeroGradients += zeros;
    // Sample the quantization error at every errorStride-th voxel of the file.
    for (uint64_t i = (errorStride - vbase % errorStride) % errorStride; i < count;
         i += errorStride) {
      if (grads[i] == format::kZeroGradient) continue;
      const double e = gradientErrorDeg(scratch.gx[i], scratch.gy[i], scratch.gz[i], grads[i]);
      ++stats.gradientSamples;
      stats.gradientErrorNanoDeg += static_cast<uint64_t>(std::llround(e * 1e9));
      stats.gradientMaxErrorDeg = std::max(stats.gradientMaxErrorDeg, e);
    }
    ++k;
  }
}

}  // namespace voxlink::convert
