// SPDX-License-Identifier: BSD-3-Clause
// How source values become stored values: the stored type, scale and offset, and the error
// that introduces. "Model only what a scene needs": integer sources whose kept range fits in
// 8 or 16 bits are stored losslessly in that many bits; lossy types are used only when asked
// for or allowed by an error bound.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>

#include "base/error.h"
#include "format/half.h"
#include "format/scalar_type.h"

namespace voxlink::convert {

struct ValueMapping {
  StoredType type = StoredType::kU8;
  double scale = 1.0;  // source = stored * scale + offset
  double offset = 0.0;
  bool quantized = false;   // integer stored type over a scaled range (lossy)
  double errorBound = 0.0;  // guaranteed max abs error of this mapping (0: lossless)
  // f32 from f64 only: every nonzero kept value stays a normal float after the scale, so the
  // relative error is at most 2^-24. False when one power-of-two scale cannot cover the kept
  // magnitudes (1e300 and 1: the small ones would flush to 0).
  bool keepsRelativeError = true;
  std::string reason;  // why this type, for the summary

  // Stored bits of a source value (already known to lie in the kept range).
  uint32_t encode(double v) const {
    const double q = (v - offset) / scale;
    switch (type) {
      case StoredType::kU8:
        return static_cast<uint32_t>(std::clamp(std::nearbyint(q), 0.0, 255.0));
      case StoredType::kU16:
        return static_cast<uint32_t>(std::clamp(std::nearbyint(q), 0.0, 65535.0));
      case StoredType::kF16:
        return format::floatToHalf(static_cast<float>(q));
      case StoredType::kF32: {
        const float f = static_cast<float>(q);
        uint32_t bits;
        std::memcpy(&bits, &f, 4);
        return bits;
      }
    }
    return 0;
  }
  double decode(uint32_t bits) const {
    double stored = 0;
    switch (type) {
      case StoredType::kU8:
      case StoredType::kU16:
        stored = bits;
        break;
      case StoredType::kF16:
        stored = format::halfToFloat(static_cast<uint16_t>(bits));
        break;
      case StoredType::kF32: {
        float f;
        std::memcpy(&f, &bits, 4);
        stored = f;
        break;
      }
    }
    return stored * scale + offset;
  }
};

// Picks the mapping for kept values in [keptMin, keptMax] of a `source` volume. `requested`
// forces a stored type; otherwise a positive `errorBound` picks the smallest type whose
// guaranteed error is within it, and 0 picks the smallest lossless type (f32 for f64 input,
// whose rounding error is then measured and reported). `keptMinMagnitude` is the smallest
// nonzero |value| kept (infinity: none or not known); f64 sources whose kept magnitudes f32
// cannot hold at its relative error are refused unless `errorBound` accepts an absolute error.
Result<ValueMapping> chooseValueMapping(ScalarType source, double keptMin, double keptMax,
                                        std::optional<StoredType> requested, double errorBound,
                                        double keptMinMagnitude = INFINITY);

}  // namespace voxlink::convert
