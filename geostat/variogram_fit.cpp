// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/variogram_fit.h"

#include <algorithm>
#include <cmath>

namespace voxlink::geostat {
namespace {

struct LinearFit {
  double nugget = 0, psill = 0, sse = INFINITY;
};

// Best non-negative (nugget, psill) for a fixed range: minimise sum w (g - n - p * s)^2 with
// s = 1 - correlation(lag).
LinearFit fitLinear(const std::vector<VariogramBin>& bins, const Variogram& unit, bool fitNugget) {
  double sw = 0, ss = 0, sg = 0, sss = 0, ssg = 0;
  std::vector<double> shape(bins.size()), weight(bins.size());
  for (size_t i = 0; i < bins.size(); ++i) {
    const double s = 1.0 - unit.correlation(bins[i].lag);
    const double w =
        static_cast<double>(bins[i].pairs) / std::max(bins[i].lag * bins[i].lag, 1e-300);
    shape[i] = s;
    weight[i] = w;
    sw += w;
    ss += w * s;
    sg += w * bins[i].gamma;
    sss += w * s * s;
    ssg += w * s * bins[i].gamma;
  }
  auto sse = [&](double n, double p) {
    double e = 0;
    for (size_t i = 0; i < bins.size(); ++i) {
      const double r = bins[i].gamma - n - p * shape[i];
      e += weight[i] * r * r;
    }
    return e;
  };
  LinearFit best;
  auto consider = [&](double n, double p) {
    if (n < 0 || p < 0) return;
    const double e = sse(n, p);
    if (e < best.sse) best = {n, p, e};
  };
  if (fitNugget) {
    const double det = sw * sss - ss * ss;
    if (std::fabs(det) > 1e-300 * sw * sss)
      consider((sg * sss - ss * ssg) / det, (sw * ssg - ss * sg) / det);
    consider(sg / sw, 0.0);  // pure nugget
  }
  if (sss > 0) consider(0.0, ssg / sss);  // no nugget
  return best;
}

}  // namespace

Result<std::vector<VariogramBin>> experimentalVariogram(
    const PointSet& points, const ExperimentalVariogramOptions& options) {
  const size_t n = points.size();
  if (n < 2)
    return makeError(ErrorCode::kInvalidArgument,
                     "experimental variogram: needs at least 2 samples, got ", n);
  const size_t stride = (n + options.maxSamples - 1) / std::max<size_t>(options.maxSamples, 1);
  Point3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (const Point3& p : points.coords)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  double diag = 0;
  for (int a = 0; a < 3; ++a) diag += (hi[a] - lo[a]) * (hi[a] - lo[a]);
  diag = std::sqrt(diag);
  const double cutoff = options.cutoff > 0 ? options.cutoff : diag / 3.0;
  const double width = options.width > 0 ? options.width : cutoff / 15.0;
  if (!(cutoff > 0) || !(width > 0))
    return makeError(ErrorCode::kInvalidArgument,
                     "experimental variogram: all samples at one location (cutoff 0)");
  const size_t binCount = static_cast<size_t>(std::ceil(cutoff / width));
  if (binCount > 100000)
    return makeError(ErrorCode::kInvalidArgument, "experimental variogram: cutoff/width gives ",
                     binCount, " bins (> 100000)");
  std::vector<double> lagSum(binCount, 0), gammaSum(binCount, 0);
  std::vector<uint64_t> pairs(binCount, 0);
  for (size_t i = 0; i < n; i += stride)
    for (size_t j = i + stride; j < n; j += stride) {
      const Point3& a = points.coords[i];
      const Point3& b = points.coords[j];
      const double h = std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                 (a[2] - b[2]) * (a[2] - b[2]));
      if (h > cutoff || h == 0) continue;  // gstat also leaves out zero-distance pairs
      const size_t bin = std::min(binCount - 1, static_cast<size_t>(h / width));
      const double d = points.values[i] - points.values[j];
      lagSum[bin] += h;
      gammaSum[bin] += 0.5 * d * d;
      ++pairs[bin];
    }
  std::vector<VariogramBin> bins;
  for (size_t b = 0; b < binCount; ++b)
    if (pairs[b] > 0)
      bins.push_back({lagSum[b] / static_cast<double>(pairs[b]),
                      gammaSum[b] / static_cast<double>(pairs[b]), pairs[b]});
  if (bins.empty())
    return makeError(ErrorCode::kInvalidArgument,
                     "experimental variogram: no pair of samples within the cutoff ", cutoff);
  return bins;
}

Result<VariogramParams> fitVariogram(const std::vector<VariogramBin>& bins,
                                     const VariogramFitOptions& options) {
  if (bins.size() < 3)
    return makeError(ErrorCode::kInvalidArgument, "variogram fit: needs at least 3 lag bins, got ",
                     bins.size());
  double maxGamma = 0, maxLag = 0, minLag = INFINITY;
  for (const VariogramBin& b : bins) {
    maxGamma = std::max(maxGamma, b.gamma);
    maxLag = std::max(maxLag, b.lag);
    minLag = std::min(minLag, b.lag);
  }
  if (!(maxGamma > 0))
    return makeError(ErrorCode::kInvalidArgument,
                     "variogram fit: the experimental variogram is 0 at every lag (all values "
                     "equal); give the model with --variogram");
  VariogramParams unitParams;
  unitParams.type = options.type;
  unitParams.smoothness = options.smoothness;
  auto evaluate = [&](double logRange, VariogramParams* out) {
    unitParams.range = std::exp(logRange);
    auto unit = Variogram::make(unitParams);
    if (!unit) return static_cast<double>(INFINITY);
    const LinearFit f = fitLinear(bins, *unit, options.fitNugget);
    if (out) {
      *out = unitParams;
      out->nugget = f.nugget;
      out->psill = f.psill;
    }
    return f.sse;
  };
  // Practical ranges from a tenth of the shortest lag to three times the cutoff.
  const double lo = std::log(std::max(minLag * 0.1, 1e-300)), hi = std::log(maxLag * 3.0);
  constexpr int kScan = 200;
  int bestStep = 0;
  double bestSse = INFINITY;
  for (int s = 0; s <= kScan; ++s) {
    const double e = evaluate(lo + (hi - lo) * s / kScan, nullptr);
    if (e < bestSse) {
      bestSse = e;
      bestStep = s;
    }
  }
  double a = lo + (hi - lo) * std::max(bestStep - 1, 0) / kScan;
  double b = lo + (hi - lo) * std::min(bestStep + 1, kScan) / kScan;
  const double golden = (std::sqrt(5.0) - 1) / 2;
  for (int it = 0; it < 100 && b - a > 1e-10; ++it) {
    const double c = b - golden * (b - a), d = a + golden * (b - a);
    if (evaluate(c, nullptr) < evaluate(d, nullptr))
      b = d;
    else
      a = c;
  }
  VariogramParams fitted;
  if (!std::isfinite(evaluate(0.5 * (a + b), &fitted)))
    return makeError(ErrorCode::kInvalidArgument, "variogram fit: no admissible ",
                     variogramTypeName(options.type), " model fits the experimental variogram");
  if (!(fitted.nugget + fitted.psill > 0))
    return makeError(ErrorCode::kInvalidArgument, "variogram fit: fitted sill is 0");
  return fitted;
}

}  // namespace voxlink::geostat
