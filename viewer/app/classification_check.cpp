#include "viewer/core/classification_check.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "convert/classification.h"

namespace voxlink::viewer {
namespace {

using format::ValueInterval;

bool empty(const ValueInterval& i) { return i.lo > i.hi || (i.lo == i.hi && (i.loOpen || i.hiOpen)); }

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
  out.keep = mergeIntervals(std::move(keep));
  return out;
}

std::vector<ValueInterval> mergeIntervals(std::vector<ValueInterval> set) {
  set.erase(std::remove_if(set.begin(), set.end(), empty), set.end());
  std::sort(set.begin(), set.end(), [](const ValueInterval& a, const ValueInterval& b) {
    return a.lo < b.lo || (a.lo == b.lo && !a.loOpen && b.loOpen);
  });
  std::vector<ValueInterval> out;
  for (const ValueInterval& i : set) {
    if (!out.empty()) {
      ValueInterval& last = out.back();
      // Overlapping, or touching at a value one of them contains.
      if (i.lo < last.hi || (i.lo == last.hi && (!i.loOpen || !last.hiOpen))) {
        if (i.hi > last.hi || (i.hi == last.hi && !i.hiOpen)) {
          last.hi = i.hi;
          last.hiOpen = i.hiOpen;
        }
        continue;
      }
    }
    out.push_back(i);
  }
  return out;
}

std::vector<ValueInterval> complementIntervals(const std::vector<ValueInterval>& set) {
  std::vector<ValueInterval> out;
  double lo = -HUGE_VAL;
  bool loOpen = true;
  for (const ValueInterval& i : mergeIntervals(set)) {
    const ValueInterval gap{lo, i.lo, loOpen, !i.loOpen};
    if (!empty(gap) && !(gap.lo == -HUGE_VAL && gap.hi == -HUGE_VAL)) out.push_back(gap);
    lo = i.hi;
    loOpen = !i.hiOpen;
  }
  const ValueInterval tail{lo, HUGE_VAL, loOpen, true};
  if (!empty(tail) && !(tail.lo == HUGE_VAL)) out.push_back(tail);
  return out;
}

std::vector<ValueInterval> intersectIntervals(const std::vector<ValueInterval>& a,
                                              const std::vector<ValueInterval>& b) {
  std::vector<ValueInterval> out;
  for (const ValueInterval& x : a)
    for (const ValueInterval& y : b) {
      ValueInterval r;
      if (x.lo > y.lo) r.lo = x.lo, r.loOpen = x.loOpen;
      else if (y.lo > x.lo) r.lo = y.lo, r.loOpen = y.loOpen;
      else r.lo = x.lo, r.loOpen = x.loOpen || y.loOpen;
      if (x.hi < y.hi) r.hi = x.hi, r.hiOpen = x.hiOpen;
      else if (y.hi < x.hi) r.hi = y.hi, r.hiOpen = y.hiOpen;
      else r.hi = x.hi, r.hiOpen = x.hiOpen || y.hiOpen;
      if (!empty(r)) out.push_back(r);
    }
  return mergeIntervals(std::move(out));
}

std::vector<ValueInterval> removedValues(const FileClassification& c) {
  return complementIntervals(c.keep);
}

std::vector<ValueInterval> visibleButRemoved(const format::TransferFunction& tf,
                                             const FileClassification& c) {
  return intersectIntervals(tf.visibleIntervals(), removedValues(c));
}

}  // namespace voxlink::viewer
