// SPDX-License-Identifier: BSD-3-Clause
// The convolution kernel of a stationary Gaussian random field on the voxel lattice: the
// lattice "square root" g of the covariance (g * g = C), computed by circulant embedding on a
// periodic grid (a DCT-I of the even covariance octant, clipped non-negative, square-rooted,
// transformed back) and truncated to a cube of half-width `radius` that holds all but
// `tolerance` of its energy, then rescaled so the field's variance is exactly the sill.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "geostat/detail/variogram.h"

namespace voxlink::geostat {

struct GrfKernel {
  std::array<bool, 3> active{true, true, true};  // axes along which the grid has > 1 voxel
  uint32_t radius = 0;                           // truncation half-width (voxels, active axes)
  // Octant values g(|dx|, |dy|, |dz|) for 0 <= d <= radius on active axes (x fastest).
  std::vector<double> octant;
  uint32_t embeddingHalfSize = 0;     // H: the periodic embedding has period 2H per active axis
  double covarianceAtHalfSize = 0;    // C(H) / sill: what periodization neglects
  double negativeEigenvalueMass = 0;  // clipped |negative eigenvalues| / sum |eigenvalues|
  double truncatedEnergy = 0;         // fraction of sum g^2 outside the cube, before rescaling
  uint64_t embeddingBytes = 0;

  uint32_t side() const { return radius + 1; }
  double at(uint32_t dx, uint32_t dy, uint32_t dz) const {
    const uint32_t s = side();
    return octant[(uint64_t{active[2] ? dz : 0} * (active[1] ? s : 1) + (active[1] ? dy : 0)) *
                      (active[0] ? s : 1) +
                  (active[0] ? dx : 0)];
  }
};

struct GrfKernelOptions {
  double tolerance = 1e-4;            // energy fraction allowed outside the truncated kernel
  double covarianceTolerance = 1e-6;  // C(H)/sill wanted at the embedding's half period
  uint64_t maxEmbeddingBytes = uint64_t{2} << 30;
};

// `variogram` lengths are in voxels. Axes with active[a] == false have one voxel.
Result<GrfKernel> makeGrfKernel(const Variogram& variogram, std::array<bool, 3> active,
                                const GrfKernelOptions& options = {});

}  // namespace voxlink::geostat
