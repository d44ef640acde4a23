#include "convert/value_mapping.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace voxlink::convert {
namespace {

using voxlink::StoredType;

// Guaranteed max abs error of storing values in [lo, hi] as `type`; infinity if impossible.
ValueMapping candidate(StoredType type, ScalarType source, double lo, double hi) {
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
      // f64 values beyond float's range (1e300) would store as infinity: scale them by a power
      // of two, which keeps the relative rounding error of f32 and is exact to undo.
      if (magnitude >= 0x1p127 && std::isfinite(magnitude))
        m.scale = std::ldexp(1.0, std::ilogb(magnitude) - 125);  // |stored| < 2^126: rounds finite
      // Within f32 rounding of the largest double, the rounded value overflows on decoding.
      if (!std::isfinite(magnitude) || !std::isfinite(m.decode(m.encode(magnitude))) ||
          !std::isfinite(m.decode(m.encode(-magnitude))))
        m.errorBound = INFINITY;
      break;
  }
  return m;
}

}  // namespace

Result<ValueMapping> chooseValueMapping(ScalarType source, double keptMin, double keptMax,
                                        std::optional<StoredType> requested, double errorBound) {
  if (!(keptMin <= keptMax)) {  // nothing kept: any type will do
    keptMin = keptMax = 0.0;
  }
  if (!(errorBound >= 0) || !std::isfinite(errorBound))
    return makeError(ErrorCode::kInvalidArgument, "--error-bound ", errorBound,
                     ": expected a finite value >= 0");
  if (requested) {
    ValueMapping m = candidate(*requested, source, keptMin, keptMax);
    if (!std::isfinite(m.errorBound))
      return makeError(ErrorCode::kInvalidArgument, "--value-type ", storedName(*requested),
                       ": kept values up to ", std::max(std::abs(keptMin), std::abs(keptMax)),
                       " do not fit its range");
    if (errorBound > 0 && m.errorBound > errorBound)
      return makeError(ErrorCode::kInvalidArgument, "--value-type ", storedName(*requested),
                       " cannot meet --error-bound ", errorBound, " over the kept range [", keptMin,
                       ", ", keptMax, "] (its bound is ", m.errorBound, ")");
    m.reason = "requested";
    return m;
  }
  const std::vector<StoredType> bySize = {StoredType::kU8, StoredType::kU16, StoredType::kF16,
                                          StoredType::kF32};
  for (StoredType type : bySize) {
    ValueMapping m = candidate(type, source, keptMin, keptMax);
    if (errorBound > 0 ? m.errorBound <= errorBound : m.errorBound == 0.0) {
      m.reason = errorBound > 0 ? cat("smallest type within error bound ", errorBound)
                                : "smallest lossless type for the kept range";
      return m;
    }
  }
  // Only f64 sources get here without a bound: f32, with its rounding error measured.
  ValueMapping m = candidate(StoredType::kF32, source, keptMin, keptMax);
  if (!std::isfinite(m.errorBound))
    return makeError(ErrorCode::kTooLarge, "kept values up to ",
                     std::max(std::abs(keptMin), std::abs(keptMax)),
                     " cannot be stored: f32 rounding overflows the largest double");
  if (errorBound > 0 && m.errorBound > errorBound)
    return makeError(ErrorCode::kInvalidArgument, "--error-bound ", errorBound,
                     ": no stored type meets it over the kept range [", keptMin, ", ", keptMax,
                     "] (f32 guarantees ", m.errorBound, ")");
  m.reason = "f32 (the widest stored type); rounding error measured";
  return m;
}

}  // namespace voxlink::convert
