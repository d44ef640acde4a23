// SPDX-License-Identifier: BSD-3-Clause
// The transfer function as the shaders read it. For u8, u16 and f16 files every stored value
// gets its own RGBA entry (exact at every voxel: trilinear sampling classifies voxels, never
// interpolated values). f32 files get the TF's breakpoints, evaluated piecewise linearly in the
// shader (shaders/transfer_function.glsl).
#pragma once

#include <cstdint>
#include <vector>

#include "format/scalar_type.h"
#include "tf/transfer_function.h"

namespace voxlink::tf {

struct TfTable {
  enum class Kind : uint32_t { kIndexed = 0, kBreakpoints = 1 };
  Kind kind = Kind::kIndexed;
  // kIndexed: RGBA (colour, unit-step opacity) of stored value i at texel i.
  // kBreakpoints: 3 texels per breakpoint u_j (ascending, source units):
  //   (u_j, 0, 0, 0), the RGBA just below u_j, the RGBA at u_j.
  std::vector<float> texels;
  uint32_t entries = 0;  // indexed entries or breakpoints
};

// `scale` and `offset` map stored to source values (header valueScale, valueOffset).
TfTable buildTfTable(const tf::TransferFunction& tf, StoredType type, double scale, double offset);

// Evaluates a kBreakpoints table like the shader does (tests check it against the TF).
std::array<double, 4> evaluateBreakpoints(const TfTable& table, double value);

}  // namespace voxlink::tf
