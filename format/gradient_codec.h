// SPDX-License-Identifier: BSD-3-Clause
// 16-bit polar encoding of gradient directions (paper, section 4.1).
//
//   code = t << 8 | p,   theta = t * pi / 254  (t = 0..254, polar angle from +z)
//                        phi   = p * pi / 128  (p = 0..255, azimuth from +x towards +y)
//   direction = (sin(theta) cos(phi), sin(theta) sin(phi), cos(theta))
//
// 255 polar steps (not 256) put both poles and the equator on the grid, so axis-aligned
// gradients (walls, slabs, shells) decode exactly. t = 255 is reserved: kZeroGradient marks a
// gradient that is zero or not finite. Encoding rounds theta and phi to the nearest step; over
// uniformly random directions the angular error is about 0.354 deg mean and 0.786 deg max
// (tests/format/gradient_codec_test.cpp measures it); shaders/gradient_codec.glsl decodes alike.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace voxlink::format {

inline constexpr uint16_t kZeroGradient = 0xFFFF;
inline constexpr int kPolarSteps = 254;    // theta steps between the poles
inline constexpr int kAzimuthSteps = 256;  // phi steps around the axis

// Encodes the direction of (x, y, z); the length does not matter. Zero, NaN or infinite
// components give kZeroGradient.
uint16_t encodeGradient(float x, float y, float z);
uint16_t encodeGradient(double x, double y, double z);

// Encodes `count` directions at once: what the converter uses. The arithmetic is in float and
// written so the compiler vectorizes it (AVX-512 or AVX2+FMA where the CPU has them, SSE
// otherwise); the result equals encodeGradient() except for directions within float rounding of
// a cell boundary, where either neighbouring cell may be chosen (deterministically on one
// machine: same input, same code).
void encodeGradients(const float* x, const float* y, const float* z, uint16_t* codes, size_t count);

// The batch encoders this CPU can run, fastest first (the first is what encodeGradients uses);
// for tests and benchmarks.
struct BatchGradientEncoder {
  const char* name;  // "avx512", "avx2", "portable"
  void (*encode)(const float* x, const float* y, const float* z, uint16_t* codes, size_t count);
};
std::vector<BatchGradientEncoder> batchGradientEncoders();

// Unit vector of a code; (0, 0, 0) for kZeroGradient and the other reserved codes (t = 255).
std::array<float, 3> decodeGradient(uint16_t code);

// True when the code is kZeroGradient or a valid direction in canonical form (p = 0 at poles).
bool isCanonicalGradientCode(uint16_t code);

// Reference encoder with acos/atan2 in double; the fast encoder must agree with it except
// for directions within rounding noise of a cell boundary.
uint16_t encodeGradientReference(double x, double y, double z);

}  // namespace voxlink::format
