#include "geostat/kd_tree.h"

#include <algorithm>
#include <cmath>

namespace voxlink::kriging {
namespace {

constexpr uint32_t kLeafSize = 12;

// Max-heap order: the farthest (then highest index) neighbour on top.
bool closer(const Neighbour& a, const Neighbour& b) {
  return a.distance < b.distance || (a.distance == b.distance && a.index < b.index);
}

double distance2(const Point3& a, const Point3& b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

}  // namespace

KdTree::KdTree(const std::vector<Point3>& points) : points_(points), order_(points.size()) {
  for (uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  if (!order_.empty()) build(0, static_cast<uint32_t>(order_.size()), 0);
}

int32_t KdTree::build(uint32_t begin, uint32_t end, int depth) {
  const int32_t id = static_cast<int32_t>(nodes_.size());
  nodes_.push_back(Node{begin, end});
  if (end - begin <= kLeafSize) return id;
  // Split the widest axis at the median.
  Point3 lo{1e308, 1e308, 1e308}, hi{-1e308, -1e308, -1e308};
  for (uint32_t i = begin; i < end; ++i)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], points_[order_[i]][a]);
      hi[a] = std::max(hi[a], points_[order_[i]][a]);
    }
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
  if (hi[axis] == lo[axis]) return id;  // all points coincide: keep a leaf
  const uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](uint32_t a, uint32_t b) { return points_[a][axis] < points_[b][axis]; });
  nodes_[id].axis = static_cast<uint8_t>(axis);
  nodes_[id].split = points_[order_[mid]][axis];
  const int32_t left = build(begin, mid, depth + 1);
  const int32_t right = build(mid, end, depth + 1);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

void KdTree::search(int32_t nodeId, const Point3& q, size_t k, double& worst2,
                    std::vector<Neighbour>& heap) const {
  const Node& node = nodes_[nodeId];
  if (node.left < 0) {
    for (uint32_t i = node.begin; i < node.end; ++i) {
      const uint32_t idx = order_[i];
      const double d2 = distance2(points_[idx], q);
      if (d2 > worst2) continue;
      const Neighbour n{idx, d2};  // squared until the end
      if (heap.size() < k) {
        heap.push_back(n);
        std::push_heap(heap.begin(), heap.end(), closer);
      } else if (closer(n, heap.front())) {
        std::pop_heap(heap.begin(), heap.end(), closer);
        heap.back() = n;
        std::push_heap(heap.begin(), heap.end(), closer);
      } else {
        continue;
      }
      if (heap.size() == k) worst2 = std::min(worst2, heap.front().distance);
    }
    return;
  }
  const double diff = q[node.axis] - node.split;
  const int32_t nearSide = diff < 0 ? node.left : node.right;
  const int32_t farSide = diff < 0 ? node.right : node.left;
  search(nearSide, q, k, worst2, heap);
  // <= keeps equal-distance candidates reachable so index tie-breaking is exact.
  if (diff * diff <= worst2) search(farSide, q, k, worst2, heap);
}

bool KdTree::collect(int32_t nodeId, const Point3& q, double radius2, size_t maxCount,
                     std::vector<uint32_t>& out) const {
  const Node& node = nodes_[nodeId];
  if (node.left < 0) {
    for (uint32_t i = node.begin; i < node.end; ++i)
      if (distance2(points_[order_[i]], q) <= radius2) {
        if (out.size() >= maxCount) return false;
        out.push_back(order_[i]);
      }
    return true;
  }
  const double diff = q[node.axis] - node.split;
  const int32_t nearSide = diff < 0 ? node.left : node.right;
  const int32_t farSide = diff < 0 ? node.right : node.left;
  if (!collect(nearSide, q, radius2, maxCount, out)) return false;
  return diff * diff > radius2 || collect(farSide, q, radius2, maxCount, out);
}

bool KdTree::within(const Point3& q, double radius, size_t maxCount,
                    std::vector<uint32_t>& out) const {
  if (nodes_.empty()) return true;
  return collect(0, q, radius * radius, maxCount, out);
}

void KdTree::nearest(const Point3& q, size_t k, double maxDistance,
                     std::vector<Neighbour>& out) const {
  out.clear();
  if (k == 0 || nodes_.empty()) return;
  double worst2 = std::isfinite(maxDistance) ? maxDistance * maxDistance : INFINITY;
  search(0, q, k, worst2, out);
  std::sort(out.begin(), out.end(), closer);
  for (Neighbour& n : out) n.distance = std::sqrt(n.distance);
}

}  // namespace voxlink::kriging
