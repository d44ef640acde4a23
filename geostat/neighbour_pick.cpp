// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/neighbour_pick.h"

#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace voxlink::geostat {
namespace {

// The k smallest (d2, index) of the candidates. The previous node p of the brick bounds this
// node's k-th distance: |d_k(q) - d_k(p)| <= |q - p|. Candidates below that band are in,
// those above it out, and only the few inside it are ranked. The bounds only save work: the
// pick is exact whatever they are, as long as fewer than k lie below and k in all up to the
// band's top (else the band is widened to everything). `ceiling` is a known upper bound on the
// k-th distance (the previous set's largest here), which narrows the band further.
void pickNearest(const Point3& q, size_t k, double ceiling, PickState& s) {
  const size_t m = s.d2.size(), words = (m + 63) / 64;
  double below = 0, above = INFINITY;
  if (s.lastKth >= 0) {
    const double dk = std::sqrt(s.lastKth);
    const double step = std::sqrt((q[0] - s.lastNode[0]) * (q[0] - s.lastNode[0]) +
                                  (q[1] - s.lastNode[1]) * (q[1] - s.lastNode[1]) +
                                  (q[2] - s.lastNode[2]) * (q[2] - s.lastNode[2]));
    below = dk > step ? (dk - step) * (dk - step) * (1 - 1e-9) : 0.0;
    above = std::min((dk + step) * (dk + step) * (1 + 1e-9), ceiling);
  }
  // Which side of the band each candidate falls, as bit masks (64 candidates a word): the
  // distances come in sample order, so a branch per candidate is a coin toss the predictor
  // loses, and a list of every candidate written per node cost as much as the comparisons.
  s.inside.resize(words);
  s.banded.resize(words);
  size_t inside = 0, banded = 0;
  for (;;) {
    inside = banded = 0;
    for (size_t w = 0; w < words; ++w) {
      const double* d = s.d2.data() + 64 * w;
      const size_t count = std::min<size_t>(64, m - 64 * w);
      uint64_t in = 0, band = 0;
      size_t b = 0;
#if defined(__SSE2__)
      const __m128d low = _mm_set1_pd(below), high = _mm_set1_pd(above);
      for (; b + 2 <= count; b += 2) {  // two candidates per compare, their bits by movmsk
        const __m128d x = _mm_loadu_pd(d + b);
        in |= uint64_t(_mm_movemask_pd(_mm_cmplt_pd(x, low))) << b;
        band |= uint64_t(_mm_movemask_pd(_mm_cmple_pd(x, high))) << b;
      }
#endif
      for (; b < count; ++b) {
        in |= uint64_t{d[b] < below} << b;
        band |= uint64_t{d[b] <= above} << b;
      }
      band &= ~in;
      s.inside[w] = in;
      s.banded[w] = band;
      inside += static_cast<size_t>(__builtin_popcountll(in));
      banded += static_cast<size_t>(__builtin_popcountll(band));
    }
    if (inside < k && inside + banded >= k) break;
    below = 0, above = INFINITY;
  }
  s.band.clear();  // the band's candidates in sample order, as ranked before
  for (size_t w = 0; w < words; ++w)
    for (uint64_t band = s.banded[w]; band != 0; band &= band - 1) {
      const uint32_t j = static_cast<uint32_t>(64 * w + static_cast<size_t>(__builtin_ctzll(band)));
      s.band.emplace_back(s.d2[j], j);
    }
  const auto nth = s.band.begin() + static_cast<long>(k - inside - 1);
  if (s.band.size() <= 8) {  // the usual few: an insertion sort, without nth_element's call
    for (size_t i = 1; i < s.band.size(); ++i)
      for (size_t j = i; j > 0 && s.band[j] < s.band[j - 1]; --j)
        std::swap(s.band[j], s.band[j - 1]);
  } else {
    std::nth_element(s.band.begin(), nth, s.band.end());
  }
  for (auto it = s.band.begin(); it <= nth; ++it)
    s.inside[it->second / 64] |= uint64_t{1} << (it->second % 64);
  s.picked.resize(k);  // exactly k bits are set now
  s.pickedD2.resize(k);
  uint32_t* picked = s.picked.data();
  double* pickedD2 = s.pickedD2.data();
  for (size_t w = 0; w < words; ++w)
    for (uint64_t in = s.inside[w]; in != 0; in &= in - 1) {
      const uint32_t j = static_cast<uint32_t>(64 * w + static_cast<size_t>(__builtin_ctzll(in)));
      *picked++ = j;
      *pickedD2++ = s.d2[j];
    }
  s.lastKth = nth->first;
  s.lastNode = q;
}

// The squared distances of s.picked's candidates (from s.d2) into s.pickedD2, and the largest
// of them. Four running maxima: one chain of dependent maxsd took a third of the time the kept
// sets save.
double gatherPicked(PickState& s) {
  const size_t n = s.picked.size();
  s.pickedD2.resize(n);
  const uint32_t* picked = s.picked.data();
  const double* d2 = s.d2.data();
  double* __restrict out = s.pickedD2.data();
  double m0 = 0, m1 = 0, m2 = 0, m3 = 0;
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    m0 = std::max(m0, out[i] = d2[picked[i]]);
    m1 = std::max(m1, out[i + 1] = d2[picked[i + 1]]);
    m2 = std::max(m2, out[i + 2] = d2[picked[i + 2]]);
    m3 = std::max(m3, out[i + 3] = d2[picked[i + 3]]);
  }
  for (; i < n; ++i) m0 = std::max(m0, out[i] = d2[picked[i]]);
  return std::max(std::max(m0, m1), std::max(m2, m3));
}

}  // namespace

// The node's k nearest candidates, ascending, in s.picked; false when none is in reach.
// Order: distance, then sample index (candidates are in sample order), as KdTree::nearest.
bool pickNeighbours(const Point3& q, size_t k, double maxDistance, PickState& s) {
  const size_t m = s.cx.size();
  s.d2.resize(m);
  const double reach2 = std::isfinite(maxDistance) ? maxDistance * maxDistance : INFINITY;
  const double *cx = s.cx.data(), *cy = s.cy.data(), *cz = s.cz.data();
  double* __restrict d2 = s.d2.data();  // so the loop keeps its pointers in registers
  for (size_t j = 0; j < m; ++j) {      // as KdTree computes them, so ties break alike
    const double dx = cx[j] - q[0], dy = cy[j] - q[1], dz = cz[j] - q[2];
    d2[j] = dx * dx + dy * dy + dz * dz;
  }
  // The previous node's k neighbours (s.picked) are this node's too iff exactly k candidates
  // lie at or below T, the largest of the set's distances here: the set's k are among them, so
  // no other candidate is. A tie at T counts more than k and is left to the full pick, which
  // breaks it by index. Adjacent nodes of a 2-D grid mostly share their set (about 60 % on
  // Walker Lake), and this count costs a fraction of the ranking.
  const bool mayKeep = s.lastKth >= 0 && s.picked.size() == k;  // a set of this brick
  const double kth = mayKeep ? gatherPicked(s) : -1;
  size_t atOrBelow = 0;
  if (mayKeep)
    for (size_t j = 0; j < m; ++j) atOrBelow += d2[j] <= kth;
  size_t inReach = m;  // without --max-distance every candidate is in reach
  if (std::isfinite(maxDistance))
    inReach =
        static_cast<size_t>(std::count_if(d2, d2 + m, [reach2](double d) { return d <= reach2; }));
  s.unchanged = false;
  if (inReach <= k) {
    s.picked.clear();
    s.pickedD2.clear();
    for (size_t j = 0; j < m; ++j)
      if (s.d2[j] <= reach2) {
        s.picked.push_back(static_cast<uint32_t>(j));
        s.pickedD2.push_back(s.d2[j]);
      }
    return !s.picked.empty();
  }
  s.unchanged = mayKeep && atOrBelow == k;
  if (s.unchanged) {
    s.lastKth = kth;  // what pickNearest leaves: the k-th distance
    s.lastNode = q;
  } else {
    pickNearest(q, k, mayKeep ? kth : INFINITY, s);
  }
  return true;
}

}  // namespace voxlink::geostat
