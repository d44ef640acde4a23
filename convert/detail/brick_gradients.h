// SPDX-License-Identifier: BSD-3-Clause
// The converter's gradient kernels: central differences of whole interior bricks (vectorized),
// and the angular error of an encoded direction. Used by the encoding pass
// (brick_encode_pass.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#if defined(__SSE4_1__)
#include <immintrin.h>
#endif

#include "format/gradient_codec.h"

namespace voxlink::convert {

// The cells of one brick in the slab window, and their keep flags (0/1 bytes).
template <class T>
struct BrickCells {
  const T* source;           // the brick's first cell
  const int64_t* stride;     // source element strides along x, y, z
  const uint8_t* flags;      // the keep flag of the brick's first cell
  const size_t* flagStride;  // flag strides along x, y, z
};

// Per-cell arrays of an interior brick, x fastest: (z*n + y)*n + x.
template <class T>
struct DenseBrick {
  float* g[3];  // central differences along x, y, z, times the scale
  T* center;    // the cell values
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
using DifferenceType =
    std::conditional_t<std::is_integral_v<T>,
                       std::conditional_t<(sizeof(T) <= 2), int32_t, int64_t>, T>;

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
// out.g[0..2][(z*n + y)*n + x], and the cell values into out.center[]. Float and integer sources
// only (double sources take the per-voxel path, which guards float overflow). Sources of up to 16
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

// The kernel keeps its __restrict parameters: GCC vectorized the scalar (32-bit integer) loop
// with them, not with the same pointers unpacked from a struct into restrict locals.
template <class T, uint32_t N>
void denseBrickGradientsN(const T* brick, const int64_t stride[3], const float scale[3],
                          const uint8_t* flags, const size_t flagStride[3], float* __restrict gx,
                          float* __restrict gy, float* __restrict gz, T* __restrict center) {
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

template <class T>
void denseBrickGradients(const BrickCells<T>& cells, uint32_t n, const float scale[3],
                         const DenseBrick<T>& out) {
  const T* s = cells.source;
  const uint8_t* f = cells.flags;
  switch (n) {
    case 4:
      return denseBrickGradientsN<T, 4>(s, cells.stride, scale, f, cells.flagStride, out.g[0],
                                        out.g[1], out.g[2], out.center);
    case 8:
      return denseBrickGradientsN<T, 8>(s, cells.stride, scale, f, cells.flagStride, out.g[0],
                                        out.g[1], out.g[2], out.center);
    case 16:
      return denseBrickGradientsN<T, 16>(s, cells.stride, scale, f, cells.flagStride, out.g[0],
                                         out.g[1], out.g[2], out.center);
    default:
      return denseBrickGradientsN<T, 32>(s, cells.stride, scale, f, cells.flagStride, out.g[0],
                                         out.g[1], out.g[2], out.center);
  }
}

}  // namespace voxlink::convert
