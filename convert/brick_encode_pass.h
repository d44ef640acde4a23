// The per-brick-row work of the converter's two passes, templated on the source element type
// T and the keep test. A job is one row of bricks (fixed bz, by; all bx), so the split of work
// does not depend on slab size or thread count, and neither does the output.
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

#if defined(__SSE4_1__)
#include <immintrin.h>
#endif

#include "convert/slab_window.h"
#include "convert/value_mapping.h"
#include "format/gradient_codec.h"
#include "format/layout.h"

namespace voxlink::convert {

struct GridShape {
  uint32_t dims[3];
  uint32_t n;
  uint32_t grid[3];
  format::AxisFrame frame;
  double spacing[3];
};

// Pass 1 output of one job.
struct CountResult {
  double keptMin = std::numeric_limits<double>::infinity();
  double keptMax = -std::numeric_limits<double>::infinity();
  bool nonFinite = false;
  uint32_t nonFiniteAt[3] = {0, 0, 0};
  double nonFiniteValue = 0;
};

// Counts kept voxels of the bricks in row (bz, by) into counts[bx]. `trackRange` asks for the
// min and max kept value (not needed for 8-bit sources, whose mapping does not depend on it).
// The keep flags of all n*n x-lines of the brick row are summed per x first (a loop the
// compiler vectorizes), then per brick.
template <class T, class Keep>
void countBrickRow(const SlabWindow& window, const GridShape& g, uint32_t bz, uint32_t by,
                   const Keep& keep, bool trackRange, uint16_t* counts, CountResult& result) {
  const uint32_t n = g.n, nx = g.dims[0];
  const uint32_t z0 = bz * n, z1 = std::min(g.dims[2], z0 + n);
  const uint32_t y0 = by * n, y1 = std::min(g.dims[1], y0 + n);
  thread_local std::vector<uint16_t> perX;  // up to n*n = 1024 flags per x: fits 16 bits
  thread_local std::vector<uint8_t> perX8;  // the same for 8-bit sources and n <= 8
  const bool small = sizeof(T) == 1 && n * n <= 255 && !trackRange;
  perX.assign(nx, 0);
  if (small) perX8.assign(nx, 0);
  uint16_t* __restrict acc = perX.data();
  uint8_t* __restrict acc8 = perX8.data();
  const Keep test = keep;  // a local copy: stores to acc cannot alias it
  T keptMin = std::numeric_limits<T>::max(), keptMax = std::numeric_limits<T>::lowest();
  for (uint32_t z = z0; z < z1; ++z) {
    const T* slice = reinterpret_cast<const T*>(window.slice(z));
    for (uint32_t y = y0; y < y1; ++y) {
      const T* __restrict row = slice + uint64_t{y} * nx;
      if constexpr (std::is_floating_point_v<T>) {
        bool finite = true;
        for (uint32_t x = 0; x < nx; ++x) finite &= std::isfinite(row[x]);
        if (!finite && !result.nonFinite) {
          uint32_t x = 0;
          while (std::isfinite(row[x])) ++x;
          result.nonFinite = true;
          result.nonFiniteAt[0] = x;
          result.nonFiniteAt[1] = y;
          result.nonFiniteAt[2] = z;
          result.nonFiniteValue = static_cast<double>(row[x]);
        }
        if (result.nonFinite) return;
      }
      if constexpr (sizeof(T) == 1) {
        // 8-bit sources: sum 64 lines at a time in 8-bit lanes (twice the lanes per vector),
        // then widen; n <= 8 bricks have at most 64 lines per row of bricks.
        if (small) {
          for (uint32_t x = 0; x < nx; ++x) acc8[x] = static_cast<uint8_t>(acc8[x] + (test(row[x]) ? 1 : 0));
          continue;
        }
      }
      for (uint32_t x = 0; x < nx; ++x) acc[x] = static_cast<uint16_t>(acc[x] + (test(row[x]) ? 1 : 0));
      if (trackRange) {
        for (uint32_t x = 0; x < nx; ++x) {
          const bool k = test(row[x]);
          keptMin = k && row[x] < keptMin ? row[x] : keptMin;
          keptMax = k && row[x] > keptMax ? row[x] : keptMax;
        }
      }
    }
  }
  if (small)
    for (uint32_t x = 0; x < nx; ++x) acc[x] = acc8[x];
  for (uint32_t bx = 0, x0 = 0; x0 < nx; ++bx, x0 += n) {
    const uint32_t x1 = std::min(nx, x0 + n);
    uint32_t c = 0;
    for (uint32_t x = x0; x < x1; ++x) c += acc[x];
    counts[bx] = static_cast<uint16_t>(counts[bx] + c);
    if (trackRange && c) {
      result.keptMin = std::min(result.keptMin, static_cast<double>(keptMin));
      result.keptMax = std::max(result.keptMax, static_cast<double>(keptMax));
    }
  }
}

// Where pass 2 writes the bricks of one slab: occupied bricks [k0, k0 + ...) and voxels
// [v0, v0 + ...) of the final sections.
struct SlabOutput {
  uint64_t k0 = 0, v0 = 0;
  uint16_t* rows = nullptr;
  uint32_t* masks = nullptr;
  uint8_t* values = nullptr;
  uint16_t* gradients = nullptr;
};

// Pass 2 statistics of one worker; sums are integers so totals do not depend on job order.
struct EncodeStats {
  double valueMin = std::numeric_limits<double>::infinity();  // decoded, source units
  double valueMax = -std::numeric_limits<double>::infinity();
  double maxAbsError = 0, maxRelError = 0;
  uint64_t gradientSamples = 0;
  uint64_t gradientErrorNanoDeg = 0;
  double gradientMaxErrorDeg = 0;
  uint64_t zeroGradients = 0;
  bool countMismatch = false;  // the source changed between the passes
};

// Angle in degrees between an exact direction and a decoded code (atan2 form: accurate for
// small angles, unlike acos of the dot product).
inline double gradientErrorDeg(double gx, double gy, double gz, uint16_t code) {
  const auto d = format::decodeGradient(code);
  const double len = std::sqrt(gx * gx + gy * gy + gz * gz);
  if (len == 0 || code == format::kZeroGradient) return 0.0;
  gx /= len;
  gy /= len;
  gz /= len;
  const double cx = gy * d[2] - gz * d[1], cy = gz * d[0] - gx * d[2], cz = gx * d[1] - gy * d[0];
  const double dot = gx * d[0] + gy * d[1] + gz * d[2];
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dot) * (180.0 / 3.14159265358979323846);
}

// Differences of two source values without losing precision: integers exactly, floats in
// their own precision (a float of 1e6 + 1e-3 would lose it), then one conversion to float.
template <class T>
using DifferenceType = std::conditional_t<std::is_integral_v<T>, std::conditional_t<(sizeof(T) <= 2), int32_t, int64_t>, T>;

// Four source values widened to four int32 lanes (integers of up to 16 bits) or four floats.
#if defined(__SSE4_1__)
template <class T>
inline __m128i widen4(const T* p) {
  if constexpr (sizeof(T) == 1) {
    int32_t bytes;
    std::memcpy(&bytes, p, 4);
    const __m128i v = _mm_cvtsi32_si128(bytes);
    return std::is_signed_v<T> ? _mm_cvtepi8_epi32(v) : _mm_cvtepu8_epi32(v);
  } else {
    const __m128i v = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(p));
    return std::is_signed_v<T> ? _mm_cvtepi16_epi32(v) : _mm_cvtepu16_epi32(v);
  }
}

template <class T>
inline __m128 difference4(const T* hi, const T* lo) {
  if constexpr (std::is_same_v<T, float>) {
    return _mm_sub_ps(_mm_loadu_ps(hi), _mm_loadu_ps(lo));
  } else {
    return _mm_cvtepi32_ps(_mm_sub_epi32(widen4(hi), widen4(lo)));
  }
}
#endif

// Central differences of every cell of an interior brick, in source order (x fastest), into
// g[0..2][(z*n + y)*n + x], and the cell values into center[]. Float and integer sources only
// (double sources take the per-voxel path, which guards float overflow). Sources of up to 16
// bits and floats are done 4 cells at a time with SSE4.1 (every x86-64-v2 target): the
// compiler's own vectorizer left this loop scalar for 8-bit input and an 8-cell brick edge,
// which made it the converter's most expensive step.
template <uint32_t N>
inline bool anyFlagSet(const uint8_t* f) {  // N keep flags (0/1 bytes) of one x line
  uint64_t any = 0;
  for (uint32_t i = 0; i < N; i += (N < 8 ? N : 8)) {
    uint64_t word = 0;
    std::memcpy(&word, f + i, N < 8 ? N : 8);
    any |= word;
  }
  return any != 0;
}

template <class T, uint32_t N>
void denseBrickGradientsN(const T* brick, const int64_t stride[3], const float scale[3],
                          const uint8_t* flags, const size_t flagStride[3],
                          float* __restrict gx, float* __restrict gy, float* __restrict gz,
                          T* __restrict center) {
  using D = DifferenceType<T>;
  const int64_t sy = stride[1], sz = stride[2];
#if defined(__SSE4_1__)
  if constexpr (sizeof(T) <= 2 || std::is_same_v<T, float>) {
    const __m128 s0 = _mm_set1_ps(scale[0]), s1 = _mm_set1_ps(scale[1]), s2 = _mm_set1_ps(scale[2]);
    for (uint32_t z = 0; z < N; ++z) {
      for (uint32_t y = 0; y < N; ++y) {
        if (!anyFlagSet<N>(flags + y * flagStride[1] + z * flagStride[2])) continue;
        const T* p = brick + z * sz + y * sy;
        const size_t o = (size_t{z} * N + y) * N;
        for (uint32_t x = 0; x < N; x += 4) {
          const T* c = p + x;
          _mm_storeu_ps(gx + o + x, _mm_mul_ps(difference4(c + 1, c - 1), s0));
          _mm_storeu_ps(gy + o + x, _mm_mul_ps(difference4(c + sy, c - sy), s1));
          _mm_storeu_ps(gz + o + x, _mm_mul_ps(difference4(c + sz, c - sz), s2));
          std::memcpy(center + o + x, c, sizeof(T) * 4);
        }
      }
    }
    return;
  }
#endif
  const float s0 = scale[0], s1 = scale[1], s2 = scale[2];
  for (uint32_t z = 0; z < N; ++z) {
    for (uint32_t y = 0; y < N; ++y) {
      if (!anyFlagSet<N>(flags + y * flagStride[1] + z * flagStride[2])) continue;
      const T* __restrict p = brick + z * sz + y * sy;
      const size_t o = (size_t{z} * N + y) * N;
      for (int64_t x = 0; x < int64_t{N}; ++x) {
        gx[o + x] = static_cast<float>(static_cast<D>(p[x + 1]) - static_cast<D>(p[x - 1])) * s0;
        gy[o + x] = static_cast<float>(static_cast<D>(p[x + sy]) - static_cast<D>(p[x - sy])) * s1;
        gz[o + x] = static_cast<float>(static_cast<D>(p[x + sz]) - static_cast<D>(p[x - sz])) * s2;
        center[o + x] = p[x];
      }
    }
  }
}

// Keep flags of every cell of a row of bricks (n slices x n rows x the whole width), x fastest.
// Long contiguous loops: they vectorize and stream the row's source data into cache in order,
// so the per-brick work that follows reads from L2 instead of striding through slices.
// Only x in [x0, x1) is filled: the span of the row's occupied bricks.
template <class T, class Keep>
void rowKeepFlags(const SlabWindow& window, const uint32_t dims[3], uint32_t z0, uint32_t z1, uint32_t y0,
                  uint32_t y1, uint32_t x0, uint32_t x1, uint32_t n, const Keep keep, uint8_t* __restrict flags) {
  const uint32_t nx = dims[0];
  for (uint32_t z = z0; z < z1; ++z) {
    const T* slice = reinterpret_cast<const T*>(window.slice(z));
    for (uint32_t y = y0; y < y1; ++y) {
      const T* __restrict p = slice + uint64_t{y} * nx;
      uint8_t* __restrict f = flags + (size_t{z - z0} * n + (y - y0)) * nx;
      for (uint32_t x = x0; x < x1; ++x) f[x] = keep(p[x]) ? 1 : 0;
    }
  }
}

template <class T>
void denseBrickGradients(const T* brick, const int64_t stride[3], uint32_t n, const float scale[3],
                         const uint8_t* flags, const size_t flagStride[3], float* gx, float* gy,
                         float* gz, T* center) {
  switch (n) {
    case 4: return denseBrickGradientsN<T, 4>(brick, stride, scale, flags, flagStride, gx, gy, gz, center);
    case 8: return denseBrickGradientsN<T, 8>(brick, stride, scale, flags, flagStride, gx, gy, gz, center);
    case 16: return denseBrickGradientsN<T, 16>(brick, stride, scale, flags, flagStride, gx, gy, gz, center);
    default: return denseBrickGradientsN<T, 32>(brick, stride, scale, flags, flagStride, gx, gy, gz, center);
  }
}

// Encodes one occupied brick: its row starts, row masks, values and gradients. `Interior`
// says the brick and a one-voxel margin lie inside the volume, so no border tests are needed.
template <class T, bool Interior>
uint32_t encodeBrick(const T* brick, const uint32_t origin[3], const uint32_t dims[3],
                     const int64_t stride[3], const format::AxisFrame frame, uint32_t n,
                     const ValueMapping& mapping, bool lossless, const double half[3],
                     const double full[3], uint32_t expected, uint16_t* rows, uint32_t* mask,
                     uint8_t* values, float* gx, float* gy, float* gz, const float* const dense[3],
                     const uint8_t* flags, const size_t flagStride[3], EncodeStats& stats) {
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
        const double err = std::abs(decoded - exact);
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
          grad[a] = (static_cast<double>(cell[stride[a]]) - static_cast<double>(cell[-stride[a]])) * half[a];
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
// advancing by the keep bit, then gathered in one loop.
template <class T, class S, uint32_t N>
uint32_t encodeInteriorBrick(const format::AxisFrame frame, const uint8_t* flags, const size_t flagStride[3],
                             const float* const dense[3], const T* __restrict center, int64_t offset,
                             uint32_t expected, uint16_t* __restrict rows, uint32_t* __restrict mask,
                             S* __restrict values, float* __restrict gx, float* __restrict gy,
                             float* __restrict gz, T& rawMin, T& rawMax) {
  constexpr uint32_t kDenseStride[3] = {1, N, N * N};
  const size_t fU = flagStride[frame.u], fV = flagStride[frame.v], fW = flagStride[frame.w];
  const uint32_t dU = kDenseStride[frame.u], dV = kDenseStride[frame.v], dW = kDenseStride[frame.w];
  // Every row's occupancy bits first. When rows run across x (u = x, the default z axis), the
  // flags of N rows are contiguous for each depth: an N*N-wide loop the compiler vectorizes.
  using Bits = std::conditional_t<(N <= 8), uint8_t, std::conditional_t<(N <= 16), uint16_t, uint32_t>>;
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
          for (uint32_t g = 0; g < N / 8; ++g) bits |= static_cast<uint32_t>((groups[g] >> (8 * j)) & 0xFF) << (8 * g);
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
  using Index = uint16_t;       // cells of a brick: at most 32^3 = 32768
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
        const __m128i positions = _mm_cvtepu8_epi16(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&kSetBitPositions[byte])));
        const __m128i cells = _mm_add_epi16(_mm_set1_epi16(static_cast<int16_t>(base + 8 * g * dW)),
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
uint32_t encodeInteriorBrick(uint32_t n, const format::AxisFrame frame, const uint8_t* flags, const size_t flagStride[3],
                             const float* const dense[3], const T* center, int64_t offset, uint32_t expected,
                             uint16_t* rows, uint32_t* mask, S* values, float* gx, float* gy, float* gz, T& rawMin, T& rawMax) {
  switch (n) {
    case 4: return encodeInteriorBrick<T, S, 4>(frame, flags, flagStride, dense, center, offset, expected, rows, mask, values, gx, gy, gz, rawMin, rawMax);
    case 8: return encodeInteriorBrick<T, S, 8>(frame, flags, flagStride, dense, center, offset, expected, rows, mask, values, gx, gy, gz, rawMin, rawMax);
    case 16: return encodeInteriorBrick<T, S, 16>(frame, flags, flagStride, dense, center, offset, expected, rows, mask, values, gx, gy, gz, rawMin, rawMax);
    default: return encodeInteriorBrick<T, S, 32>(frame, flags, flagStride, dense, center, offset, expected, rows, mask, values, gx, gy, gz, rawMin, rawMax);
  }
}

template <class T, class Keep>
void encodeBrickRow(const SlabWindow& window, const GridShape& g, uint32_t bz, uint32_t by,
                    const Keep& keep, const ValueMapping& mapping, const uint16_t* counts,
                    uint64_t firstOccupied, const uint32_t* voxelBase, const SlabOutput& out,
                    uint32_t errorStride, EncodeStats& stats) {
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
    std::vector<float> gx, gy, gz;           // gradients of the brick's kept voxels
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
  const uint32_t z0 = bz * n, z1 = std::min(dims[2], z0 + n);
  const uint32_t y0 = by * n, y1 = std::min(dims[1], y0 + n);
  scratch.flags.resize(size_t{n} * n * dims[0]);
  rowKeepFlags<T>(window, dims, z0, z1, y0, y1, bxFirst * n, std::min(dims[0], bxEnd * n), n, keep, scratch.flags.data());
  const size_t flagStride[3] = {1, dims[0], size_t{n} * dims[0]};
  if (kDense) {
    scratch.denseX.resize(cells);
    scratch.denseY.resize(cells);
    scratch.denseZ.resize(cells);
    scratch.denseV.resize(cells);
  }
  const float halfF[3] = {static_cast<float>(half[0]), static_cast<float>(half[1]), static_cast<float>(half[2])};

  uint64_t k = firstOccupied;
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
    const uint8_t* flags = scratch.flags.data() + origin[0];
    const float* dense[3] = {nullptr, nullptr, nullptr};
    if (kDense && interior) {  // only x lines with a kept cell: the others are never read
      denseBrickGradients(brick, stride, n, halfF, flags, flagStride, scratch.denseX.data(), scratch.denseY.data(),
                          scratch.denseZ.data(), scratch.denseV.data());
      dense[0] = scratch.denseX.data();
      dense[1] = scratch.denseY.data();
      dense[2] = scratch.denseZ.data();
    }
    float* const out3[3] = {scratch.gx.data(), scratch.gy.data(), scratch.gz.data()};
    // The tight path when it applies (interior, dense gradients, lossless u8/u16/f32 values).
    uint32_t count = UINT32_MAX;
    const bool f32Copy = std::is_same_v<T, float> && mapping.type == StoredType::kF32 &&
                         mapping.scale == 1.0 && mapping.offset == 0.0;
    if (kDense && interior && (lossless || f32Copy)) {
      T rawMin = std::numeric_limits<T>::max(), rawMax = std::numeric_limits<T>::lowest();
      const int64_t offset = static_cast<int64_t>(mapping.offset);
      if (mapping.type == StoredType::kU8)
        count = encodeInteriorBrick<T, uint8_t>(n, g.frame, flags, flagStride, dense, scratch.denseV.data(), offset, counts[bx], rows, mask,
                                                values, out3[0], out3[1], out3[2], rawMin, rawMax);
      else if (mapping.type == StoredType::kU16)
        count = encodeInteriorBrick<T, uint16_t>(n, g.frame, flags, flagStride, dense, scratch.denseV.data(), offset, counts[bx], rows, mask,
                                                 reinterpret_cast<uint16_t*>(values), out3[0], out3[1], out3[2], rawMin, rawMax);
      else if constexpr (std::is_same_v<T, float>)
        count = encodeInteriorBrick<T, float>(n, g.frame, flags, flagStride, dense, scratch.denseV.data(), offset, counts[bx], rows, mask,
                                              reinterpret_cast<float*>(values), out3[0], out3[1], out3[2], rawMin, rawMax);
      if (count != UINT32_MAX && count > 0) {
        stats.valueMin = std::min(stats.valueMin, static_cast<double>(rawMin));
        stats.valueMax = std::max(stats.valueMax, static_cast<double>(rawMax));
      }
    } else {
      count = interior ? encodeBrick<T, true>(brick, origin, dims, stride, g.frame, n, mapping, lossless, half, full,
                                              counts[bx], rows, mask, values, out3[0], out3[1], out3[2], dense, flags, flagStride, stats)
                 : encodeBrick<T, false>(brick, origin, dims, stride, g.frame, n, mapping, lossless, half, full,
                                               counts[bx], rows, mask, values, out3[0], out3[1], out3[2], dense, flags, flagStride, stats);
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
    for (uint64_t i = (errorStride - vbase % errorStride) % errorStride; i < count; i += errorStride) {
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
