// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/detail/classification_check.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "convert/classification.h"

namespace voxlink::viewer {
namespace {

using tf::ValueInterval;

ValueInterval everything() { return {-HUGE_VAL, HUGE_VAL, true, true}; }

}  // namespace

FileClassification fileClassification(const format::VoxLinkFile& file) {
  FileClassification out;
  out.keep = {everything()};
  out.description = "not recorded (everything assumed kept)";
  nlohmann::json meta;
  try {
    meta = nlohmann::json::parse(file.metaJson());
  } catch (const nlohmann::json::exception&) {
    return out;
  }
  if (!meta.is_object() || !meta.contains("classification")) return out;
  auto c = convert::classificationFromJson(meta["classification"]);
  if (!c) return out;
  out.recorded = true;
  out.description = c->describe();
  if (c->kind == convert::Classification::Kind::kAll || c->keep.empty()) return out;
  std::vector<ValueInterval> keep = c->keep;
  if (c->mean && c->sigma && *c->sigma > 0)
    for (ValueInterval& i : keep) {
      i.lo = i.lo * *c->sigma + *c->mean;
      i.hi = i.hi * *c->sigma + *c->mean;
    }
  out.keep = tf::mergeIntervals(std::move(keep));
  return out;
}

std::vector<ValueInterval> removedValues(const FileClassification& c) {
  return tf::complementIntervals(c.keep);
}

std::vector<ValueInterval> visibleButRemoved(const tf::TransferFunction& tf,
                                             const FileClassification& c) {
  return tf::intersectIntervals(tf.visibleIntervals(), removedValues(c));
}

}  // namespace voxlink::viewer
