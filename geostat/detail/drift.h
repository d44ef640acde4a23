// SPDX-License-Identifier: BSD-3-Clause
// The trend of universal kriging and kriging with an external drift: the value is modelled as
// sum_j beta_j f_j(x) plus a zero-mean residual with the variogram, the beta_j unknown. f_0 = 1
// (ordinary kriging is the drift {1}); then the coordinates (linear: x, y[, z]; quadratic adds
// their squares and products) and an external variable known at samples and nodes.
//
// Conditioning: the coordinate terms use model-space coordinates (centred on the samples'
// bounding box) divided by its half-extent, the external term is centred on its sample mean and
// divided by its standard deviation, so UTM-sized inputs give terms of order 1. Kriging
// predictions do not depend on this scaling (the same span of functions).
//
// Solvers factor C = L L^T, form U = L^-1 F (F: the drift terms at the samples, n x p) and
// G = U^T U. A node with y = L^-1 c and drift f0 then has a = U^T y - f0, mu = G^-1 a, estimate
// m + r.y - mu.(U^T r) and variance sill - y.y + mu.a (r = L^-1 (z - m)).
//
// Degenerate drift (all samples of a neighbourhood on a line under a linear drift, an external
// drift constant over a neighbourhood): G is singular. Terms that are linear combinations of
// earlier ones over the neighbourhood are dropped from that system (pivoted on the order
// above: constant, coordinates, external) and counted; the node is kriged with the rest.
#pragma once

#include <cstddef>
#include <vector>

#include "geostat/point_set.h"

namespace voxlink::geostat {

enum class DriftKind { kNone, kLinear, kQuadratic };

struct DriftBasis {
  DriftKind kind = DriftKind::kNone;
  int dimension = 2;           // 2: no z terms
  bool constant = true;        // false: simple kriging (no drift at all)
  bool external = false;       // an external drift term last
  double coordinateScale = 1;  // model-space half-extent of the samples
  double externalMean = 0, externalScale = 1;

  size_t terms() const;
  // Whether at() reads its point (ordinary kriging's single term, 1, does not).
  bool usesPoint() const { return constant && (kind != DriftKind::kNone || external); }
  // The terms at model-space point q with external drift value `external`, into f[0..terms()).
  void at(const Point3& q, double external, double* f) const;
};

// G = U^T U for U = L^-1 F, factored with dependent terms dropped.
class DriftSystem {
 public:
  // Column j of U starts at u + j * ld; n rows, p columns.
  void factor(const double* u, size_t n, size_t ld, size_t p);
  // a <- G^-1 a over the kept terms; dropped terms get 0.
  void solve(double* a) const;
  // A node's correction: with y = L^-1 c and its drift terms f0, a = U^T y - f0 and
  // mu = G^-1 a; value -= mu.ur (ur = U^T r), variance += mu.a. `scratch` holds 2 p doubles.
  void correct(const double* u, size_t n, const double* y, const double* f0, const double* ur,
               double* scratch, double& value, double& variance) const;
  // The same with the products u_j.y already formed (uy: p of them; it may be scratch).
  void correctWithProducts(const double* uy, const double* f0, const double* ur, double* scratch,
                           double& value, double& variance) const {
    if (p_ == 1 && dropped_ == 0) {  // ordinary kriging, inline: solve()'s two divisions
      const double a = uy[0] - f0[0];
      const double mu = a / g_[0] / g_[0];
      value -= mu * ur[0];
      variance += mu * a;
      return;
    }
    correctAny(uy, f0, ur, scratch, value, variance);
  }
  size_t dropped() const { return dropped_; }
  size_t size() const { return p_; }

 private:
  void correctAny(const double* uy, const double* f0, const double* ur, double* scratch,
                  double& value, double& variance) const;

  size_t p_ = 0, dropped_ = 0;
  std::vector<double> g_;  // row-major p x p; lower factor over the kept terms
  std::vector<char> kept_;
};

}  // namespace voxlink::geostat
