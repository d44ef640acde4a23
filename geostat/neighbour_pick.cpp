// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/neighbour_pick.h"

#include <algorithm>
#include <cmath>

namespace voxlink::geostat {
namespace {

// The k smallest (d2, index) of the candidates. The previous node p of the brick bounds this
// node's k-th distance: |d_k(q) - d_k(p)| <= |q - p|. Candidates below that band are in,
// those above it out, and only the few inside it are ranked. The bounds only save work: the
// pick is exact whatever they are, as long as fewer than k lie below and k in all up to the
// band's top (else the band is widened to everything).
void pickNearest(const Point3& q, size_t k, PickState& s) {
  const size_t m = s.d2.size();
  double below = 0, above = INFINITY;
  if (s.lastKth >= 0) {
    const double dk = std::sqrt(s.lastKth);
    const double step = std::sqrt((q[0] - s.lastNode[0]) * (q[0] - s.lastNode[0]) +
                                  (q[1] - s.lastNode[1]) * (q[1] - s.lastNode[1]) +
                                  (q[2] - s.lastNode[2]) * (q[2] - s.lastNode[2]));
    below = dk > step ? (dk - step) * (dk - step) * (1 - 1e-9) : 0.0;
    above = (dk + step) * (dk + step) * (1 + 1e-9);
  }
  // Branch-free passes: the distances come in sample order, so which side of the band a
  // candidate falls is a coin toss the branch predictor loses (it was most of solveNode).
  s.band.resize(m);
  s.taken.resize(m);
  size_t inside = 0, banded = 0;
  for (;;) {
    inside = banded = 0;
    for (size_t j = 0; j < m; ++j) {
      const double d = s.d2[j];
      const bool in = d < below;
      s.taken[j] = in;
      s.band[banded] = {d, static_cast<uint32_t>(j)};
      banded += !in & (d <= above);
      inside += in;
    }
    if (inside < k && inside + banded >= k) break;
    below = 0, above = INFINITY;
  }
  const auto nth = s.band.begin() + static_cast<long>(k - inside - 1);
  std::nth_element(s.band.begin(), nth, s.band.begin() + static_cast<long>(banded));
  for (auto it = s.band.begin(); it <= nth; ++it) s.taken[it->second] = 1;
  s.picked.resize(m);
  size_t picked = 0;
  for (size_t j = 0; j < m; ++j) {
    s.picked[picked] = static_cast<uint32_t>(j);
    picked += s.taken[j];
  }
  s.picked.resize(picked);
  s.lastKth = nth->first;
  s.lastNode = q;
}

}  // namespace

// The node's k nearest candidates, ascending, in s.picked; false when none is in reach.
// Order: distance, then sample index (candidates are in sample order), as KdTree::nearest.
bool pickNeighbours(const Point3& q, size_t k, double maxDistance, PickState& s) {
  const size_t m = s.cx.size();
  s.d2.resize(m);
  const double reach2 = std::isfinite(maxDistance) ? maxDistance * maxDistance : INFINITY;
  size_t inReach = 0;
  for (size_t j = 0; j < m; ++j) {  // as KdTree computes them, so ties break alike
    const double dx = s.cx[j] - q[0], dy = s.cy[j] - q[1], dz = s.cz[j] - q[2];
    s.d2[j] = dx * dx + dy * dy + dz * dz;
    inReach += s.d2[j] <= reach2;
  }
  s.picked.clear();
  if (inReach <= k) {
    for (size_t j = 0; j < m; ++j)
      if (s.d2[j] <= reach2) s.picked.push_back(static_cast<uint32_t>(j));
    return !s.picked.empty();
  }
  pickNearest(q, k, s);
  return true;
}

}  // namespace voxlink::geostat
