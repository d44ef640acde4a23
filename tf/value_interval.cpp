// SPDX-License-Identifier: BSD-3-Clause
#include "tf/value_interval.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace voxlink::tf {
namespace {

bool empty(const ValueInterval& i) {
  return i.lo > i.hi || (i.lo == i.hi && (i.loOpen || i.hiOpen));
}

}  // namespace

bool anyContains(const std::vector<ValueInterval>& set, double v) {
  for (const ValueInterval& i : set)
    if (i.contains(v)) return true;
  return false;
}

std::string describeIntervals(const std::vector<ValueInterval>& set) {
  if (set.empty()) return "{}";
  std::ostringstream out;
  out.precision(10);
  for (size_t k = 0; k < set.size(); ++k) {
    const ValueInterval& i = set[k];
    if (k) out << " u ";
    out << (i.loOpen || std::isinf(i.lo) ? '(' : '[');
    if (std::isinf(i.lo))
      out << "-inf";
    else
      out << i.lo;
    out << ", ";
    if (std::isinf(i.hi))
      out << "inf";
    else
      out << i.hi;
    out << (i.hiOpen || std::isinf(i.hi) ? ')' : ']');
  }
  return out.str();
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
      if (x.lo > y.lo)
        r.lo = x.lo, r.loOpen = x.loOpen;
      else if (y.lo > x.lo)
        r.lo = y.lo, r.loOpen = y.loOpen;
      else
        r.lo = x.lo, r.loOpen = x.loOpen || y.loOpen;
      if (x.hi < y.hi)
        r.hi = x.hi, r.hiOpen = x.hiOpen;
      else if (y.hi < x.hi)
        r.hi = y.hi, r.hiOpen = y.hiOpen;
      else
        r.hi = x.hi, r.hiOpen = x.hiOpen || y.hiOpen;
      if (!empty(r)) out.push_back(r);
    }
  return mergeIntervals(std::move(out));
}

}  // namespace voxlink::tf
