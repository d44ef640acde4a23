// SPDX-License-Identifier: BSD-3-Clause
// Transfer functions: piecewise-linear opacity and colour over source values, and their JSON
// file format (docs/transfer-function.md). Shared by the converter (which voxels are visible)
// and the viewer (how they look).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "base/error.h"
#include "tf/value_interval.h"

namespace voxlink::tf {

struct OpacityPoint {
  double value;
  double alpha;  // opacity of one unit step (the smallest voxel spacing), in [0, 1]
};

struct ColorPoint {
  double value;
  std::array<double, 3> rgb;  // linear RGB in [0, 1]
};

struct TransferFunction {
  std::string name;
  std::vector<OpacityPoint> opacity;  // sorted by value; clamped beyond the ends
  std::vector<ColorPoint> color;      // sorted by value; clamped beyond the ends

  double opacityAt(double value) const;
  std::array<double, 3> colorAt(double value) const;
  // Exactly the values with opacity > 0 (linear pieces make this a finite union).
  std::vector<ValueInterval> visibleIntervals() const;
};

// Parses the project's TF JSON; `where` (a file name) prefixes error messages.
Result<TransferFunction> parseTransferFunction(const std::string& json, const std::string& where);
Result<TransferFunction> loadTransferFunction(const std::string& path);
std::string transferFunctionJson(const TransferFunction& tf);
Status saveTransferFunction(const TransferFunction& tf, const std::string& path);

}  // namespace voxlink::tf
