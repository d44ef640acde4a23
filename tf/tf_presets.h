// SPDX-License-Identifier: BSD-3-Clause
// Built-in transfer functions laid over a value range, the TF a file opens with, and import of
// ParaView colour-map presets (the JSON ParaView's "Export preset" writes).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "base/error.h"
#include "format/voxlink_file.h"
#include "tf/transfer_function.h"

namespace voxlink::tf {

std::vector<std::string> tfPresetNames();  // "ct-bone", "ct-soft-tissue", ...
// The preset stretched over [lo, hi] (source units); fails on an unknown name or lo >= hi.
Result<tf::TransferFunction> tfPreset(const std::string& name, double lo, double hi);

// [lo, hi] with lo < hi, both finite, for showing a stored range [valueMin, valueMax]: a single
// value (even 1e20 or the largest double) gets a width, a NaN or infinite bound is replaced.
std::pair<double, double> displayRange(double lo, double hi);

// What a file opens with: the TF recorded in META (classification.tf) when there is one,
// otherwise "ct-bone" over the stored value range.
tf::TransferFunction defaultTransferFunction(const format::VoxLinkFile& file);

// Reads a ParaView preset file (an array of presets, or one object) and returns the preset named
// `name`, or the first one when `name` is empty. RGBPoints become colour points, Points (x, alpha,
// midpoint, sharpness) become opacity points (midpoint and sharpness are ignored). When
// `rescaleTo` is given (lo < hi), the preset's x range is stretched onto it, as ParaView does when
// it applies a preset to data. Presets without Points get an opacity ramp over the range.
struct ParaViewImport {
  std::string name;
  double lo = 0, hi = 0;  // rescale target; ignored when lo >= hi
};
Result<tf::TransferFunction> importParaViewPreset(const std::string& path,
                                                  const ParaViewImport& options);
Result<tf::TransferFunction> parseParaViewPreset(const std::string& json, const std::string& where,
                                                 const ParaViewImport& options);

}  // namespace voxlink::tf
