#include "format/value_interval.h"

#include <cmath>
#include <sstream>

namespace voxlink::format {

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
    if (std::isinf(i.lo)) out << "-inf"; else out << i.lo;
    out << ", ";
    if (std::isinf(i.hi)) out << "inf"; else out << i.hi;
    out << (i.hiOpen || std::isinf(i.hi) ? ')' : ']');
  }
  return out.str();
}

}  // namespace voxlink::format
