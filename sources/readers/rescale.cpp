// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/rescale.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

namespace voxlink::sources {
namespace {

bool integral(double v) { return std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 1e15; }

template <class T>
bool holds(double lo, double hi) {
  return lo >= static_cast<double>(std::numeric_limits<T>::lowest()) &&
         hi <= static_cast<double>(std::numeric_limits<T>::max());
}

class RescaledSource final : public VolumeSource {
 public:
  RescaledSource(std::unique_ptr<VolumeSource> inner, double slope, double intercept,
                 ScalarType outType, std::string note)
      : inner_(std::move(inner)), slope_(slope), intercept_(intercept) {
    info_ = inner_->info();
    info_.type = outType;
    info_.notes.push_back(std::move(note));
  }

  bool randomAccess() const override { return inner_->randomAccess(); }
  Status rewind() override { return inner_->rewind(); }

  Status read(uint32_t z0, uint32_t count, void* dst) override {
    const VolumeInfo& in = inner_->info();
    const uint64_t voxels = uint64_t{count} * in.sliceVoxels();
    try {
      scratch_.resize(voxels * scalarSize(in.type));
    } catch (const std::bad_alloc&) {
      return makeError(ErrorCode::kTooLarge, info_.path, ": ", count,
                       " slices do not fit in memory");
    }
    VOXLINK_RETURN_IF_ERROR(inner_->read(z0, count, scratch_.data()));
    convertRescaled(scratch_.data(), in.type, dst, info_.type, voxels, slope_, intercept_);
    return Status::ok();
  }

 private:
  std::unique_ptr<VolumeSource> inner_;
  double slope_;
  double intercept_;
  std::vector<uint8_t> scratch_;
};

}  // namespace

ScalarType typeForValueRange(ScalarType stored, double lo, double hi, bool integralValues) {
  if (!isFloat(stored) && integralValues) {
    if (holds<uint8_t>(lo, hi)) return ScalarType::kU8;
    if (holds<int8_t>(lo, hi)) return ScalarType::kI8;
    if (holds<uint16_t>(lo, hi)) return ScalarType::kU16;
    if (holds<int16_t>(lo, hi)) return ScalarType::kI16;
    if (holds<uint32_t>(lo, hi)) return ScalarType::kU32;
    if (holds<int32_t>(lo, hi)) return ScalarType::kI32;
  }
  const bool wide =
      stored == ScalarType::kF64 || stored == ScalarType::kI32 || stored == ScalarType::kU32;
  return wide ? ScalarType::kF64 : ScalarType::kF32;
}

ScalarType rescaledType(ScalarType stored, double storedMin, double storedMax, double slope,
                        double intercept) {
  const double a = storedMin * slope + intercept, b = storedMax * slope + intercept;
  return typeForValueRange(stored, std::min(a, b), std::max(a, b),
                           integral(slope) && integral(intercept));
}

void convertRescaled(const void* src, ScalarType srcType, void* dst, ScalarType dstType,
                     uint64_t count, double slope, double intercept) {
  dispatchScalar(srcType, [&](auto storedTag) {
    using S = decltype(storedTag);
    const auto* in = static_cast<const S*>(src);
    dispatchScalar(dstType, [&](auto outTag) {
      using O = decltype(outTag);
      auto* out = static_cast<O*>(dst);
      if constexpr (std::is_integral_v<O>) {
        const auto m = static_cast<int64_t>(slope), b = static_cast<int64_t>(intercept);
        for (uint64_t i = 0; i < count; ++i)
          out[i] = static_cast<O>(static_cast<int64_t>(in[i]) * m + b);
      } else {
        for (uint64_t i = 0; i < count; ++i)
          out[i] = static_cast<O>(static_cast<double>(in[i]) * slope + intercept);
      }
    });
  });
}

std::unique_ptr<VolumeSource> rescaleSource(std::unique_ptr<VolumeSource> inner, double slope,
                                            double intercept, ScalarType outType,
                                            const std::string& fieldNames) {
  const ScalarType storedType = inner->info().type;
  std::string note = cat(fieldNames, " applied: value = stored ", scalarName(storedType), " * ",
                         slope, " + ", intercept, ", served as ", scalarName(outType));
  return std::make_unique<RescaledSource>(std::move(inner), slope, intercept, outType,
                                          std::move(note));
}

}  // namespace voxlink::sources
