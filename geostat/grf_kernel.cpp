// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/grf_kernel.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <new>

namespace voxlink::geostat {
namespace {

struct FftwFree {
  void operator()(double* p) const { fftw_free(p); }
};

// Smallest h (voxels) with correlation(h) <= tol; correlation decreases for every model here.
double distanceForCorrelation(const Variogram& v, double tol) {
  double hi = v.params().range;
  while (v.correlation(hi) > tol && hi < 1e9) hi *= 2;
  double lo = 0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (v.correlation(mid) > tol)
      lo = mid;
    else
      hi = mid;
  }
  return hi;
}

}  // namespace

Result<GrfKernel> makeGrfKernel(const Variogram& variogram, std::array<bool, 3> active,
                                const GrfKernelOptions& options) {
  GrfKernel k;
  k.active = active;
  const int dimension = int{active[0]} + int{active[1]} + int{active[2]};
  if (dimension == 0)
    return makeError(ErrorCode::kInvalidArgument,
                     "random field: the grid has one voxel; nothing to correlate");
  const double sill = variogram.sill();
  // Without a correlated part the field is white noise: a one-voxel kernel.
  double wanted = variogram.params().psill > 0
                      ? std::ceil(distanceForCorrelation(variogram, options.covarianceTolerance))
                      : 1.0;
  // Compactly supported models (spherical) need room beyond the range too, or the periodic
  // square root cannot decay inside the period.
  wanted = std::max({wanted, 2.0 * std::ceil(variogram.params().range), 4.0});
  const double maxPoints = static_cast<double>(options.maxEmbeddingBytes / sizeof(double));
  const double maxHalf = std::floor(std::pow(maxPoints, 1.0 / dimension)) - 1;
  const uint32_t H = static_cast<uint32_t>(std::min(wanted, maxHalf));
  if (H < 2)
    return makeError(ErrorCode::kTooLarge, "random field: no room for the covariance embedding");
  k.embeddingHalfSize = H;
  k.covarianceAtHalfSize = variogram.correlation(H) * variogram.params().psill / sill;
  const uint32_t n = H + 1;
  const uint32_t nx = active[0] ? n : 1, ny = active[1] ? n : 1, nz = active[2] ? n : 1;
  const uint64_t count = uint64_t{nx} * ny * nz;
  k.embeddingBytes = count * sizeof(double);
  std::unique_ptr<double, FftwFree> buffer(
      static_cast<double*>(fftw_malloc(count * sizeof(double))));
  if (!buffer)
    return makeError(ErrorCode::kTooLarge, "random field: cannot allocate ", k.embeddingBytes,
                     " bytes for the covariance embedding");
  double* c = buffer.get();
  for (uint32_t z = 0; z < nz; ++z)
    for (uint32_t y = 0; y < ny; ++y)
      for (uint32_t x = 0; x < nx; ++x) {
        const double h = std::sqrt(double(x) * x + double(y) * y + double(z) * z);
        c[(uint64_t{z} * ny + y) * nx + x] = variogram.covariance(h);
      }
  int dims[3];
  int rank = 0;
  for (int a = 2; a >= 0; --a)
    if (active[a]) dims[rank++] = static_cast<int>(n);
  const fftw_r2r_kind kinds[3] = {FFTW_REDFT00, FFTW_REDFT00, FFTW_REDFT00};
  fftw_plan plan = fftw_plan_r2r(rank, dims, c, c, kinds, FFTW_ESTIMATE);
  fftw_execute(plan);  // eigenvalues of the periodic covariance (period 2H)
  double negative = 0, total = 0;
  for (uint64_t i = 0; i < count; ++i) {
    total += std::fabs(c[i]);
    if (c[i] < 0) {
      negative += -c[i];
      c[i] = 0;
    }
    c[i] = std::sqrt(c[i]);
  }
  k.negativeEigenvalueMass = total > 0 ? negative / total : 0;
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  const double scale = 1.0 / std::pow(2.0 * H, dimension);  // REDFT00 twice = 2H per axis
  // Energy per cube shell max(|dx|,|dy|,|dz|) = s, counting each octant cell's mirror images
  // (a coordinate 0 or H has one image along its axis, the others two).
  std::vector<double> shell(n, 0.0);
  double energy = 0;
  for (uint32_t z = 0; z < nz; ++z)
    for (uint32_t y = 0; y < ny; ++y)
      for (uint32_t x = 0; x < nx; ++x) {
        double& g = c[(uint64_t{z} * ny + y) * nx + x];
        g *= scale;
        double images = 1;
        for (uint32_t d : {active[0] ? x : 0u, active[1] ? y : 0u, active[2] ? z : 0u})
          images *= (d == 0 || d == H) ? 1 : 2;
        const double e = images * g * g;
        shell[std::max({x, y, z})] += e;
        energy += e;
      }
  // The cube stops short of H, where the periodic kernel has one image instead of two.
  uint32_t radius = 0;
  double kept = shell[0];
  while (radius + 1 < H && kept < (1.0 - options.tolerance) * energy) kept += shell[++radius];
  k.radius = radius;
  k.truncatedEnergy = energy > 0 ? 1.0 - kept / energy : 0;
  const double rescale = kept > 0 ? std::sqrt(sill / kept) : 0;
  const uint32_t s = radius + 1;
  const uint32_t sx = active[0] ? s : 1, sy = active[1] ? s : 1, sz = active[2] ? s : 1;
  try {
    k.octant.resize(uint64_t{sx} * sy * sz);
  } catch (const std::bad_alloc&) {
    return makeError(ErrorCode::kTooLarge, "random field: the kernel of radius ", radius,
                     " voxels (", uint64_t{sx} * sy * sz * sizeof(double),
                     " bytes) does not fit in memory beside its embedding; use a shorter range");
  }
  for (uint32_t z = 0; z < sz; ++z)
    for (uint32_t y = 0; y < sy; ++y)
      for (uint32_t x = 0; x < sx; ++x)
        k.octant[(uint64_t{z} * sy + y) * sx + x] = c[(uint64_t{z} * ny + y) * nx + x] * rescale;
  return k;
}

}  // namespace voxlink::geostat
