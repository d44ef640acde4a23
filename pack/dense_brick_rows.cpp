// SPDX-License-Identifier: BSD-3-Clause
#include "pack/detail/dense_brick_rows.h"

#include <array>
#include <bit>

#include "format/brick_rows.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define VOXLINK_DENSE_BRICK_ROWS 1
#endif

namespace voxlink::pack {

using format::rowBits;

#ifdef VOXLINK_DENSE_BRICK_ROWS
namespace {

// For each 8-bit group of a row's mask: kExpand[m][j] is the value (counted from the group's
// first) that lane j takes when bit j is set; kCompress[m] lists the set lanes in order.
struct LaneTables {
  std::array<std::array<uint8_t, 8>, 256> expand{}, compress{};
};
constexpr LaneTables makeLaneTables() {
  LaneTables t;
  for (int m = 0; m < 256; ++m) {
    int k = 0;
    for (int j = 0; j < 8; ++j)
      if (m >> j & 1) {
        t.expand[m][j] = static_cast<uint8_t>(k);
        t.compress[m][k++] = static_cast<uint8_t>(j);
      }
  }
  return t;
}
constexpr LaneTables kLanes = makeLaneTables();

[[gnu::target("avx2")]] inline __m256i laneIndex(const std::array<uint8_t, 8>& lanes) {
  return _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(lanes.data())));
}

// (c[step] - c[-step]) * h of eight cells, the set ones (`order`) moved to the front.
[[gnu::target("avx2")]] inline __m256 setDifferences(const float* c, uint32_t step, __m256 h,
                                                     __m256i order) {
  const __m256 d = _mm256_sub_ps(_mm256_loadu_ps(c + step), _mm256_loadu_ps(c - step));
  return _mm256_permutevar8x32_ps(_mm256_mul_ps(d, h), order);
}

[[gnu::target("avx2")]] inline uint32_t expandCells(uint32_t bits, uint32_t n, const float* values,
                                                    float fill, float* cells) {
  const __m256 fills = _mm256_set1_ps(fill);
  const __m256i laneBit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  uint32_t i = 0;
  for (uint32_t g = 0; g < n / 8; ++g) {
    const uint32_t m = bits >> (8 * g) & 0xFFu;
    const __m256 spread =
        _mm256_permutevar8x32_ps(_mm256_loadu_ps(values + i), laneIndex(kLanes.expand[m]));
    const __m256i set = _mm256_cmpeq_epi32(
        _mm256_and_si256(_mm256_set1_epi32(static_cast<int>(m)), laneBit), laneBit);
    _mm256_storeu_ps(cells + 8 * g, _mm256_blendv_ps(fills, spread, _mm256_castsi256_ps(set)));
    i += static_cast<uint32_t>(std::popcount(m));
  }
  return i;
}

}  // namespace

bool denseBrickRowsAvailable() {
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

[[gnu::target("avx2")]] uint32_t expandBrickRows(const uint32_t* brickMask, uint32_t n,
                                                 const float* values, float fill, float* block) {
  const uint32_t p = n + 2;
  uint32_t i = 0, row = 0;
  for (uint32_t v = 1; v <= n; ++v)
    for (uint32_t u = 1; u <= n; ++u, ++row)
      i +=
          expandCells(rowBits(brickMask, n, row), n, values + i, fill, block + 1 + p * (u + p * v));
  return i;
}

[[gnu::target("avx2")]] void expandRows(const uint32_t* bits, uint32_t rows, uint32_t n,
                                        const float* values, float fill, float* cells,
                                        uint32_t step) {
  for (uint32_t r = 0; r < rows; ++r)
    values += expandCells(bits[r], n, values, fill, cells + r * step);
}

[[gnu::target("avx2")]] uint32_t brickCentralDifferences(const uint32_t* brickMask, uint32_t n,
                                                         const float* block, const float half[3],
                                                         float* gw, float* gu, float* gv) {
  const uint32_t p = n + 2, groups = n / 8;
  const __m256 hw = _mm256_set1_ps(half[0]), hu = _mm256_set1_ps(half[1]),
               hv = _mm256_set1_ps(half[2]);
  uint32_t i = 0, row = 0;
  for (uint32_t v = 1; v <= n; ++v)
    for (uint32_t u = 1; u <= n; ++u, ++row) {
      const uint32_t bits = rowBits(brickMask, n, row);
      if (bits == 0) continue;
      const float* cells = block + 1 + p * (u + p * v);
      for (uint32_t g = 0; g < groups; ++g) {
        const uint32_t m = bits >> (8 * g) & 0xFFu;
        if (m == 0) continue;
        const float* c = cells + 8 * g;
        const __m256i order = laneIndex(kLanes.compress[m]);
        _mm256_storeu_ps(gw + i, setDifferences(c, 1, hw, order));
        _mm256_storeu_ps(gu + i, setDifferences(c, p, hu, order));
        _mm256_storeu_ps(gv + i, setDifferences(c, p * p, hv, order));
        i += static_cast<uint32_t>(std::popcount(m));
      }
    }
  return i;
}

#else  // no AVX2 kernels: the prediction keeps its per-voxel path

bool denseBrickRowsAvailable() { return false; }
uint32_t expandBrickRows(const uint32_t*, uint32_t, const float*, float, float*) { return 0; }
void expandRows(const uint32_t*, uint32_t, uint32_t, const float*, float, float*, uint32_t) {}
uint32_t brickCentralDifferences(const uint32_t*, uint32_t, const float*, const float[3], float*,
                                 float*, float*) {
  return 0;
}

#endif

}  // namespace voxlink::pack
