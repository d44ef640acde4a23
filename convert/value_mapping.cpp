// SPDX-License-Identifier: BSD-3-Clause
#include "convert/detail/value_mapping.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace voxlink::convert {
namespace {

using voxlink::StoredType;

// f64 values keep f32's relative error (2^-24) when, after one power-of-two scale 2^k (exact to
// undo), the largest is below 2^127 (it rounds to a finite float) and the smallest nonzero one
// is still a normal float (>= 2^-126): exponents at most 252 apart. Beyond float's range (1e300)
// k is set by the largest, below it (1e-300) by the smallest, and is 0 in between, as before.
void scaleF64IntoF32(ValueMapping& m, double magnitude, double minMagnitude) {
  if (!(magnitude > 0) || !std::isfinite(magnitude)) return;
  const int top = std::ilogb(magnitude);
  const int bottom =
      minMagnitude > 0 && std::isfinite(minMagnitude) ? std::ilogb(minMagnitude) : top;
  int k = 0;
  if (top >= 127) k = top - 125;
  if (bottom - k < -126) k = std::max(bottom + 126, top - 126);
  m.scale = std::ldexp(1.0, k);
  m.keepsRelativeError = bottom - k >= -126;
}

// Guaranteed max abs error of storing values in [lo, hi] as `type`, as an export gives them back
// in the source's type (integers rounded); infinity if impossible.
ValueMapping candidate(StoredType type, ScalarType source, double lo, double hi,
                       double minMagnitude) {
  ValueMapping m;
  m.type = type;
  const double range = hi - lo;
  const double magnitude = std::max(std::abs(lo), std::abs(hi));
  const bool integral = !isFloat(source);
  switch (type) {
    case StoredType::kU8:
    case StoredType::kU16: {
      const double levels = type == StoredType::kU8 ? 255.0 : 65535.0;
      if (integral && range <= levels) {
        // Lossless: stored = value - offset. u8 sources keep their values as they are.
        m.offset = (lo >= 0 && hi <= levels) ? 0.0 : lo;
        m.errorBound = 0.0;
      } else {
        m.quantized = true;
        m.offset = lo;
        m.scale = range > 0 ? range / levels : 1.0;
        m.errorBound = range > 0 ? m.scale / 2 : 0.0;
        // An integer source is given back rounded to whole numbers: a level within scale / 2
        // of the value rounds to a whole number at most floor(scale / 2 + 0.5) from it.
        if (integral) m.errorBound = std::floor(m.errorBound + 0.5);
      }
      break;
    }
    case StoredType::kF16:
      // Half ulp relative (2^-11) for normal halves, 2^-25 absolute in the subnormal range.
      m.errorBound = magnitude > 65504.0 ? INFINITY : std::max(magnitude * 0x1p-11, 0x1p-25);
      if (integral && magnitude <= 2048) m.errorBound = 0.0;  // integers up to 2048 are exact
      break;
    case StoredType::kF32:
      m.errorBound = (integral && magnitude <= 16777216.0) || source == ScalarType::kF32
                         ? 0.0
                         : magnitude * 0x1p-24;
      // f32 sources are stored as they are (a scale would flush their subnormals); f64 values
      // outside float's normal range are scaled by a power of two.
      if (source == ScalarType::kF64) scaleF64IntoF32(m, magnitude, minMagnitude);
      // Within f32 rounding of the largest double, the rounded value overflows on decoding.
      if (!std::isfinite(magnitude) || !std::isfinite(m.decode(m.encode(magnitude))) ||
          !std::isfinite(m.decode(m.encode(-magnitude))))
        m.errorBound = INFINITY;
      break;
  }
  return m;
}

// f32 cannot keep every kept f64 value at its relative error: the user has to accept an
// absolute error (--error-bound) or keep fewer values.
Error relativeErrorLost(double magnitude, double minMagnitude, const ValueMapping& f32) {
  return makeError(ErrorCode::kUnsupported, "data: kept values range in magnitude from ",
                   minMagnitude, " to ", magnitude,
                   ", wider than f32 holds at its relative error 2^-24 (one scale; exponents "
                   "at most 252 apart): the smallest would come back as 0 or with a larger error. "
                   "Give --error-bound E to accept an absolute error (f32 meets E >= ",
                   f32.errorBound, ") or keep a narrower range (--threshold)");
}

}  // namespace

Result<ValueMapping> chooseValueMapping(ScalarType source, double keptMin, double keptMax,
                                        std::optional<StoredType> requested, double errorBound,
                                        double keptMinMagnitude) {
  if (!(keptMin <= keptMax)) {  // nothing kept: any type will do
    keptMin = keptMax = 0.0;
  }
  if (!(errorBound >= 0) || !std::isfinite(errorBound))
    return makeError(ErrorCode::kInvalidArgument, "--error-bound ", errorBound,
                     ": expected a finite value >= 0");
  if (requested) {
    ValueMapping m = candidate(*requested, source, keptMin, keptMax, keptMinMagnitude);
    if (!std::isfinite(m.errorBound))
      return makeError(ErrorCode::kInvalidArgument, "--value-type ", storedName(*requested),
                       ": kept values up to ", std::max(std::abs(keptMin), std::abs(keptMax)),
                       " do not fit its range");
    if (errorBound > 0 && m.errorBound > errorBound)
      return makeError(ErrorCode::kInvalidArgument, "--value-type ", storedName(*requested),
                       " cannot meet --error-bound ", errorBound, " over the kept range [", keptMin,
                       ", ", keptMax, "] (its bound is ", m.errorBound, ")");
    if (!m.keepsRelativeError && errorBound == 0)
      return relativeErrorLost(std::max(std::abs(keptMin), std::abs(keptMax)), keptMinMagnitude, m);
    m.reason = "requested";
    return m;
  }
  const std::vector<StoredType> bySize = {StoredType::kU8, StoredType::kU16, StoredType::kF16,
                                          StoredType::kF32};
  for (StoredType type : bySize) {
    ValueMapping m = candidate(type, source, keptMin, keptMax, keptMinMagnitude);
    if (errorBound > 0 ? m.errorBound <= errorBound : m.errorBound == 0.0) {
      m.reason = errorBound > 0 ? cat("smallest type within error bound ", errorBound)
                                : "smallest lossless type for the kept range";
      return m;
    }
  }
  // Only f64 sources get here without a bound: f32, with its rounding error measured.
  ValueMapping m = candidate(StoredType::kF32, source, keptMin, keptMax, keptMinMagnitude);
  if (!std::isfinite(m.errorBound))
    return makeError(ErrorCode::kTooLarge, "kept values up to ",
                     std::max(std::abs(keptMin), std::abs(keptMax)),
                     " cannot be stored: f32 rounding overflows the largest double");
  if (errorBound > 0 && m.errorBound > errorBound)
    return makeError(ErrorCode::kInvalidArgument, "--error-bound ", errorBound,
                     ": no stored type meets it over the kept range [", keptMin, ", ", keptMax,
                     "] (f32 guarantees ", m.errorBound, ")");
  if (!m.keepsRelativeError && errorBound == 0)
    return relativeErrorLost(std::max(std::abs(keptMin), std::abs(keptMax)), keptMinMagnitude, m);
  m.reason = "f32 (the widest stored type); rounding error measured";
  return m;
}

}  // namespace voxlink::convert
