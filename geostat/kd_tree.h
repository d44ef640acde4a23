// A k-d tree over 3-D points for the k nearest neighbours of a location within a radius:
// what keeps kriging with 10^4-10^5 samples at O(k^3) per grid node instead of O(n^3).
#pragma once

#include <cstdint>
#include <vector>

#include "geostat/point_set.h"

namespace voxlink::kriging {

struct Neighbour {
  uint32_t index;   // into the point list the tree was built from
  double distance;  // Euclidean
};

class KdTree {
 public:
  explicit KdTree(const std::vector<Point3>& points);

  // The up to `k` points nearest to `q` with distance <= maxDistance, nearest first; ties at
  // equal distance are ordered by point index so results never depend on tree shape.
  void nearest(const Point3& q, size_t k, double maxDistance, std::vector<Neighbour>& out) const;
  // Appends the indices of the points within `radius` of q (any order) to `out`; stops and
  // returns false once more than maxCount were found, so a crowded ball costs little.
  bool within(const Point3& q, double radius, size_t maxCount, std::vector<uint32_t>& out) const;

 private:
  struct Node {
    uint32_t begin, end;  // range in order_
    int32_t left = -1, right = -1;
    uint8_t axis = 0;
    double split = 0;
  };
  int32_t build(uint32_t begin, uint32_t end, int depth);
  void search(int32_t node, const Point3& q, size_t k, double& worst2,
              std::vector<Neighbour>& heap) const;
  bool collect(int32_t node, const Point3& q, double radius2, size_t maxCount,
               std::vector<uint32_t>& out) const;

  std::vector<Point3> points_;  // own copy: the tree outlives moves of its creator
  std::vector<uint32_t> order_;
  std::vector<Node> nodes_;
};

}  // namespace voxlink::kriging
