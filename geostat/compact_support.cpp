// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/compact_support.h"

#include <cmath>
#include <limits>

namespace voxlink::geostat {

double covarianceReach(const Variogram& v) {
  // Spherical: correlation(h) is 0 for h >= range (variogram.cpp). The others only underflow.
  return v.params().type == VariogramType::kSpherical ? v.params().range
                                                      : std::numeric_limits<double>::infinity();
}

SupportGatherer::SupportGatherer(const Kriger& kriger)
    : kriger_(kriger), buckets_(kriger.centredSamples(), covarianceReach(kriger.variogram())) {}

void SupportGatherer::gather(const Point3& q, NodeSupport& s) const {
  s.index.clear();
  s.covariance.clear();
  s.candidates.clear();
  buckets_.candidates(q, s.candidates);
  const auto& p = kriger_.centredSamples();
  const Variogram& v = kriger_.variogram();
  for (const uint32_t i : s.candidates) {
    const double dx = p[i][0] - q[0], dy = p[i][1] - q[1], dz = p[i][2] - q[2];
    const double c = v.covariance(std::sqrt(dx * dx + dy * dy + dz * dz));
    if (c != 0) {
      s.index.push_back(i);
      s.covariance.push_back(c);
    }
  }
}

SparseForms sparseForms(const InverseSystem& inverse, const NodeSupport& s, size_t terms,
                        double* wc) {
  const size_t n = inverse.n, m = s.index.size();
  const uint32_t* idx = s.index.data();
  const double* c = s.covariance.data();
  SparseForms f;
  for (size_t k = 0; k < m; ++k) {
    // Row idx[k] of the symmetric K^-1 is its column: contiguous for the gathers below.
    const double* column = &inverse.kinv[idx[k] * n];
    double offDiagonal = 0;
    for (size_t l = 0; l < k; ++l) offDiagonal += column[idx[l]] * c[l];
    f.quadratic += c[k] * (2 * offDiagonal + column[idx[k]] * c[k]);
    f.dotAlpha += c[k] * inverse.alpha[idx[k]];
  }
  for (size_t j = 0; j < terms; ++j) {
    const double* wj = &inverse.w[j * n];
    double sum = 0;
    for (size_t k = 0; k < m; ++k) sum += wj[idx[k]] * c[k];
    wc[j] = sum;
  }
  return f;
}

}  // namespace voxlink::geostat
