// SPDX-License-Identifier: BSD-3-Clause
// Isotropic variogram models with nugget, partial sill and range, and the covariance each one
// implies (C(h) = nugget + psill - gamma(h) for h > 0, C(0) = nugget + psill).
//
// Range convention: `range` is always the PRACTICAL range, the distance at which the
// correlation of the structured part falls to exp(-3) ~ 5 % (the usual factor 3 of the
// exponential and Gaussian models; spherical: exactly its sill). In gstat's terms:
//   exponential  vgm(psill, "Exp", range / 3, nugget)
//   spherical    vgm(psill, "Sph", range, nugget)
//   gaussian     vgm(psill, "Gau", range / sqrt(3), nugget)
//   matern       vgm(psill, "Mat", scale(), nugget, kappa = smoothness)
// where scale() is the Matern scale parameter solved so that correlation(range) = exp(-3).
#pragma once

#include <cstddef>
#include <string>

#include "base/error.h"

namespace voxlink::geostat {

enum class VariogramType { kExponential, kSpherical, kGaussian, kMatern };

const char* variogramTypeName(VariogramType type);

struct VariogramParams {
  VariogramType type = VariogramType::kExponential;
  double nugget = 0.0;
  double psill = 1.0;       // partial sill of the correlated part
  double range = 1.0;       // practical range, in coordinate units
  double smoothness = 0.5;  // Matern nu (0.5 = exponential); ignored by the other types
};

class Variogram {
 public:
  // Checks the parameters (finite, nugget >= 0, psill >= 0, sill > 0, range > 0,
  // 0.05 <= smoothness <= 50 for Matern) and precomputes the Matern scale.
  static Result<Variogram> make(const VariogramParams& params);

  const VariogramParams& params() const { return params_; }
  double sill() const { return params_.nugget + params_.psill; }
  // Correlation of the structured part at distance h >= 0 (1 at h = 0).
  double correlation(double h) const;
  // Covariance of two samples at distance h; h == 0 includes the nugget.
  double covariance(double h) const { return h == 0.0 ? sill() : params_.psill * correlation(h); }
  // out[i] = covariance(sqrt(squared[i])) for n distances, bit for bit: one switch and a loop
  // vectorized four wide where AVX2 runs (spherical) or exp() four at a time (exponential), not
  // a call per distance (local kriging's right-hand side).
  void covariancesOfSquared(const double* squared, double* out, size_t n) const;
  // out[i] = covariance(h[i]) for n distances, bit for bit (the exponential model's exp() four
  // at a time, the spherical model's loop four wide: local kriging's pair covariances).
  void covariances(const double* h, double* out, size_t n) const;
  double gamma(double h) const {
    return h == 0.0 ? 0.0 : params_.nugget + params_.psill * (1.0 - correlation(h));
  }
  // Matern scale parameter (phi in rho(h) = 2^(1-nu)/Gamma(nu) (h/phi)^nu K_nu(h/phi)).
  double maternScale() const { return maternScale_; }
  // "matern(nugget=0, psill=1, range=30, nu=1.5)"-style description for summaries.
  std::string describe() const;

 private:
  VariogramParams params_;
  double maternScale_ = 1.0;
  double maternNorm_ = 1.0;  // 2^(1-nu) / Gamma(nu)
};

// Parses "TYPE:key=value,..." with TYPE in exp, sph, gau, mat and keys nugget, psill (or
// sill, the total), range, nu. Example: "sph:nugget=0.1,psill=0.9,range=40".
Result<VariogramParams> parseVariogram(const std::string& text);

}  // namespace voxlink::geostat
