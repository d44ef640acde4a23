// SPDX-License-Identifier: BSD-3-Clause
// Pre-classification: which source values a VoxLink file keeps. Thresholds, a transfer
// function's visible range, or values outside an interval (confidence intervals) all reduce
// to a union of value intervals, recorded in the file's META section.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "tf/transfer_function.h"
#include "tf/value_interval.h"

namespace voxlink::convert {

struct Classification {
  enum class Kind { kThreshold, kTransferFunction, kKeepOutside, kAll };
  Kind kind = Kind::kAll;
  std::vector<tf::ValueInterval> keep;     // what survives, in source units
  std::optional<tf::TransferFunction> tf;  // when kind == kTransferFunction
  // Keep-outside may first standardize values: z = (v - mean) / sigma.
  std::optional<double> mean, sigma;

  bool keeps(double sourceValue) const;
  std::string describe() const;  // one line for summaries
};

// `--threshold 60` keeps [60, inf); `--threshold 60,200` keeps [60, 200]; several are a union.
Result<Classification> thresholdClassification(const std::vector<std::string>& specs);
Classification tfClassification(const tf::TransferFunction& tf);
// Keeps values strictly outside [lo, hi] (after standardizing when mean/sigma are given).
Result<Classification> keepOutsideClassification(double lo, double hi, std::optional<double> mean,
                                                 std::optional<double> sigma);
Classification keepAllClassification();

nlohmann::json classificationToJson(const Classification& c);
Result<Classification> classificationFromJson(const nlohmann::json& j);

}  // namespace voxlink::convert
