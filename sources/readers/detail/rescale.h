// SPDX-License-Identifier: BSD-3-Clause
// value = stored * slope + intercept, applied while slices stream (DICOM RescaleSlope/Intercept,
// NIfTI scl_slope/scl_inter).
#pragma once

#include <memory>

#include "sources/volume_source.h"

namespace voxlink::sources {

// The type the rescaled values are served as. With an integral slope and intercept, the
// smallest of u8, i8, u16, i16, u32, i32 that holds [storedMin, storedMax] mapped through the
// rescale (exact); otherwise f32, or f64 when the stored type is f64, i32 or u32 (f32 could not
// hold their values exactly).
ScalarType rescaledType(ScalarType stored, double storedMin, double storedMax, double slope,
                        double intercept);
// The same rule for values already known to lie in [lo, hi]; `integral` says they are integers.
ScalarType typeForValueRange(ScalarType stored, double lo, double hi, bool integral);

// dst[i] = src[i] * slope + intercept, converted to dstType. With an integer dstType the
// slope and intercept must be integers (exact integer arithmetic).
void convertRescaled(const void* src, ScalarType srcType, void* dst, ScalarType dstType,
                     uint64_t count, double slope, double intercept);

// Wraps `inner`, serving inner values * slope + intercept as `outType` (from rescaledType()).
// Adds a note saying what was applied. Memory: one scratch buffer of the slices asked for.
std::unique_ptr<VolumeSource> rescaleSource(std::unique_ptr<VolumeSource> inner, double slope,
                                            double intercept, ScalarType outType,
                                            const std::string& fieldNames);

}  // namespace voxlink::sources
