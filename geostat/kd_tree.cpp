// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/kd_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nanoflann.hpp>

namespace voxlink::geostat {
namespace {

constexpr size_t kLeafSize = 12;

// nanoflann keeps a leaf's point when its distance is below the result set's worstDist(), and
// prunes a branch whose lower bound (summed over axes, so a few ulps off) is above it. Asking
// with a bound this much larger lets every point at exactly the bound through to the result
// sets, which then decide by the exact comparisons below.
constexpr double kBoundMargin = 1 + 1e-12;

// Max-heap order: the farthest (then highest index) neighbour on top.
bool closer(const Neighbour& a, const Neighbour& b) {
  return a.distance < b.distance || (a.distance == b.distance && a.index < b.index);
}

struct Cloud {
  std::vector<Point3> points;
  size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(uint32_t i, size_t axis) const { return points[i][axis]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

// Squared distances as local_kriging.cpp computes them (p - q, x then y then z), so that both
// break ties alike.
struct SquaredDistance {
  using ElementType = double;
  using DistanceType = double;
  const Cloud& cloud;
  explicit SquaredDistance(const Cloud& c) : cloud(c) {}
  double evalMetric(const double* q, uint32_t i, size_t) const {
    const Point3& p = cloud.points[i];
    const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    return dx * dx + dy * dy + dz * dz;
  }
  double accum_dist(double a, double b, size_t) const { return (a - b) * (a - b); }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<SquaredDistance, Cloud, 3, uint32_t>;

// The k nearest by (squared distance, index) within a squared bound: a max-heap.
class NearestSet {
 public:
  NearestSet(size_t k, double bound2, std::vector<Neighbour>& heap)
      : k_(k), bound2_(bound2), heap_(heap), worst_(widened(bound2)) {}
  bool full() const { return heap_.size() == k_; }
  // nanoflann asks at every leaf point and branch: kept, not recomputed (nextafter is a call).
  double worstDist() const { return worst_; }
  bool addPoint(double d2, uint32_t index) {
    const Neighbour n{index, d2};  // squared until the end
    if (d2 > bound2_) return true;
    if (!full()) {
      heap_.push_back(n);
      std::push_heap(heap_.begin(), heap_.end(), closer);
    } else if (closer(n, heap_.front())) {
      std::pop_heap(heap_.begin(), heap_.end(), closer);
      heap_.back() = n;
      std::push_heap(heap_.begin(), heap_.end(), closer);
    } else {
      return true;
    }
    if (full()) worst_ = widened(std::min(bound2_, heap_.front().distance));
    return true;
  }

 private:
  static double widened(double d2) { return std::nextafter(d2 * kBoundMargin, INFINITY); }
  size_t k_;
  double bound2_;
  std::vector<Neighbour>& heap_;
  double worst_;
};

// Every point within a squared radius, stopping once there are more than maxCount.
class BallSet {
 public:
  BallSet(double radius2, size_t maxCount, std::vector<uint32_t>& out,
          std::vector<double>* squared = nullptr)
      : radius2_(radius2),
        worst_(std::nextafter(radius2 * kBoundMargin, INFINITY)),
        maxCount_(maxCount),
        out_(out),
        squared_(squared) {}
  bool full() const { return true; }
  // Asked at every leaf point and branch: kept, as NearestSet keeps its bound.
  double worstDist() const { return worst_; }
  bool addPoint(double d2, uint32_t index) {
    if (d2 > radius2_) return true;
    if (found_ >= maxCount_) {
      overflow_ = true;
      return false;
    }
    ++found_;
    out_.push_back(index);
    if (squared_) squared_->push_back(d2);
    return true;
  }
  bool overflow() const { return overflow_; }

 private:
  double radius2_, worst_;
  size_t maxCount_;
  std::vector<uint32_t>& out_;
  std::vector<double>* squared_;
  size_t found_ = 0;
  bool overflow_ = false;
};

}  // namespace

struct KdTree::Index {
  Cloud cloud;
  Tree tree;
  explicit Index(const std::vector<Point3>& points)
      : cloud{points}, tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize)) {}
};

KdTree::KdTree(const std::vector<Point3>& points) : index_(std::make_unique<Index>(points)) {}

KdTree::~KdTree() = default;

bool KdTree::within(const Point3& q, double radius, size_t maxCount,
                    std::vector<uint32_t>& out) const {
  if (index_->cloud.points.empty()) return true;
  BallSet ball(radius * radius, maxCount, out);
  index_->tree.findNeighbors(ball, q.data(), nanoflann::SearchParams());
  return !ball.overflow();
}

bool KdTree::within(const Point3& q, double radius, size_t maxCount, std::vector<uint32_t>& out,
                    std::vector<double>& squared) const {
  if (index_->cloud.points.empty()) return true;
  BallSet ball(radius * radius, maxCount, out, &squared);
  index_->tree.findNeighbors(ball, q.data(), nanoflann::SearchParams());
  return !ball.overflow();
}

void KdTree::nearest(const Point3& q, size_t k, double maxDistance,
                     std::vector<Neighbour>& out) const {
  out.clear();
  if (k == 0 || index_->cloud.points.empty()) return;
  const double bound2 = std::isfinite(maxDistance) ? maxDistance * maxDistance : INFINITY;
  NearestSet set(k, bound2, out);
  index_->tree.findNeighbors(set, q.data(), nanoflann::SearchParams());
  std::sort(out.begin(), out.end(), closer);
  for (Neighbour& n : out) n.distance = std::sqrt(n.distance);
}

}  // namespace voxlink::geostat
