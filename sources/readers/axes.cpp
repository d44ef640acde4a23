// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/axes.h"

#include <cmath>

#include "base/error.h"

namespace voxlink::sources {

double length(const Vec3& v) { return std::sqrt(dot(v, v)); }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

AxesSummary summarizeAxes(const std::array<Vec3, 3>& axes, std::string_view source) {
  constexpr double kTolerance = 1e-6;  // relative; below it a component counts as zero
  AxesSummary s;
  bool oblique = false;
  bool identity = true;
  std::string directions;
  for (int i = 0; i < 3; ++i) {
    const Vec3& v = axes[i];
    s.lengths[i] = length(v);
    int major = 0;
    for (int c = 1; c < 3; ++c)
      if (std::fabs(v[c]) > std::fabs(v[major])) major = c;
    for (int c = 0; c < 3; ++c)
      if (c != major && std::fabs(v[c]) > kTolerance * s.lengths[i]) oblique = true;
    const bool negative = v[major] < 0;
    if (major != i || negative) identity = false;
    directions += cat(i ? " " : "", negative ? "-" : "+", "xyz"[major]);
  }
  if (oblique) {
    s.note = cat(source, " are oblique (not along the coordinate axes): only their lengths are ",
                 "used as spacing; voxels stay in index order");
  } else if (!identity) {
    s.note = cat(source, " run along ", directions, ": only their lengths are used as spacing; ",
                 "voxels stay in index order (no flip or permutation applied)");
  }
  return s;
}

}  // namespace voxlink::sources
