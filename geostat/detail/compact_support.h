// SPDX-License-Identifier: BSD-3-Clause
// Global kriging with a covariance that is exactly 0 beyond a finite distance (spherical: its
// range). With K^-1 formed once, a node's estimate m + c.alpha (alpha = K^-1 (z - m)), its
// variance sill - c^T K^-1 c and its drift terms a = (K^-1 F)^T c - f0 need only the samples
// where the node's covariance vector c is not 0: nnz^2 work per node instead of n^2. Exact: the
// terms left out are products with exact zeros.
#pragma once

#include <cstdint>
#include <vector>

#include "geostat/detail/kriging.h"
#include "geostat/detail/sample_buckets.h"

namespace voxlink::geostat {

// The distance from which the model's covariance is exactly 0 (spherical: the range); +inf for
// the models without compact support (exponential, Gaussian, Matern).
double covarianceReach(const Variogram& v);

// K^-1 and what the nodes' formulas take from it.
struct InverseSystem {
  size_t n = 0;
  std::vector<double> kinv;   // K^-1, n x n, column-major, both triangles
  std::vector<double> alpha;  // K^-1 (z - m)
  std::vector<double> w;      // K^-1 F, drift term j's column at j * n
};

// A node's nonzero covariances with the samples, and scratch for the lookup.
struct NodeSupport {
  std::vector<uint32_t> index;
  std::vector<double> covariance;
  std::vector<uint32_t> candidates;
};

class SupportGatherer {
 public:
  // For a kriger whose covariance has a finite reach.
  explicit SupportGatherer(const Kriger& kriger);
  // The samples whose covariance with model-space point q is not 0, with those covariances
  // (computed as the dense path computes them, so the nonzero values are the same bits).
  void gather(const Point3& q, NodeSupport& s) const;

 private:
  const Kriger& kriger_;
  SampleBuckets buckets_;
};

// Over the node's support: c.alpha, c^T K^-1 c, and (K^-1 F)^T c into wc[0, terms).
struct SparseForms {
  double dotAlpha = 0, quadratic = 0;
};
SparseForms sparseForms(const InverseSystem& inverse, const NodeSupport& s, size_t terms,
                        double* wc);

}  // namespace voxlink::geostat
