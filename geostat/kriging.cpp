// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/kriging.h"

#include <algorithm>
#include <numeric>

namespace voxlink::geostat {
namespace {

// Kriger::predict factors one dense system per call: 128 MiB per thread, O(n^3) each. Grids
// krige globally with one factorization whatever the size (global_kriging.cpp).
constexpr size_t kMaxSystemSize = 4096;

double distance(const Point3& a, const Point3& b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

}  // namespace

Error singularSystemError(size_t n, double maxCondition) {
  return makeError(ErrorCode::kInvalidArgument, "kriging: the covariance matrix of ", n,
                   " samples stays singular (condition > ", maxCondition,
                   ") even with a diagonal jitter of ", kLastJitter,
                   " x sill; merge near-duplicate samples (--merge-distance) or add a nugget");
}

Point3 Kriger::modelCoordinates(const Point3& p) const {
  const Point3 c{p[0] - centre_[0], p[1] - centre_[1], p[2] - centre_[2]};
  if (!anisotropic_) return c;
  // Along the long range (angle clockwise from +y) and across it, stretched by 1 / ratio.
  return {c[0] * sine_ + c[1] * cosine_, (c[0] * cosine_ - c[1] * sine_) / options_.anisotropyRatio,
          c[2]};
}

Point3 Kriger::sample(size_t i) const {
  Point3 c = coords_[i];
  if (anisotropic_) {
    const double along = c[0], across = c[1] * options_.anisotropyRatio;
    c[0] = along * sine_ + across * cosine_;
    c[1] = along * cosine_ - across * sine_;
  }
  return {c[0] + centre_[0], c[1] + centre_[1], c[2] + centre_[2]};
}

Result<Kriger> Kriger::make(const PointSet& points, const Variogram& variogram,
                            const KrigingOptions& options) {
  if (points.size() == 0) return makeError(ErrorCode::kInvalidArgument, "kriging: no samples");
  if (options.kind == KrigingKind::kSimple && !std::isfinite(options.simpleMean))
    return makeError(ErrorCode::kInvalidArgument, "kriging: simple kriging needs a finite --mean");
  if (options.maxNeighbours > kMaxSystemSize && options.maxNeighbours < points.size())
    return makeError(ErrorCode::kTooLarge, "kriging: neighbourhoods of ", options.maxNeighbours,
                     " samples need a dense system per node (limit ", kMaxSystemSize,
                     "); use --neighbours 16..256");
  if (!(options.anisotropyRatio > 0 && options.anisotropyRatio <= 1) ||
      !std::isfinite(options.anisotropyAngle))
    return makeError(ErrorCode::kInvalidArgument,
                     "kriging: --anisotropy needs a finite angle and a ratio in (0, 1], got ",
                     options.anisotropyAngle, ",", options.anisotropyRatio);
  const bool drifts = options.drift != DriftKind::kNone || options.externalDrift;
  if (drifts && options.kind == KrigingKind::kSimple)
    return makeError(ErrorCode::kInvalidArgument,
                     "kriging: simple kriging has a known mean; --drift and --external-drift need "
                     "--kind ok");
  if (options.externalDrift && points.drift.size() != points.size())
    return makeError(ErrorCode::kInvalidArgument,
                     "kriging: external drift asked for but the samples have no drift column");
  // A condition number is at least 1; below it (or NaN) every system would fail the jitter ladder.
  if (!(options.maxCondition >= 1))
    return makeError(ErrorCode::kInvalidArgument, "kriging: --max-condition must be >= 1, got ",
                     options.maxCondition);
  if (!(options.maxDistance > 0))
    return makeError(ErrorCode::kInvalidArgument, "kriging: --max-distance must be > 0, got ",
                     options.maxDistance);
  Point3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < points.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(points.coords[i][a]))
        return makeError(ErrorCode::kNonFinite, "kriging: sample ", i,
                         " has a non-finite coordinate");
      lo[a] = std::min(lo[a], points.coords[i][a]);
      hi[a] = std::max(hi[a], points.coords[i][a]);
    }
    if (!std::isfinite(points.values[i]))
      return makeError(ErrorCode::kNonFinite, "kriging: sample ", i, " has a non-finite value");
  }
  Kriger k(variogram);
  k.options_ = options;
  for (int a = 0; a < 3; ++a) k.centre_[a] = 0.5 * (lo[a] + hi[a]);
  k.anisotropic_ = options.anisotropyRatio < 1;
  k.cosine_ = std::cos(options.anisotropyAngle * M_PI / 180);
  k.sine_ = std::sin(options.anisotropyAngle * M_PI / 180);
  const double diagonal = distance(lo, hi);
  if (k.options_.mergeDistance < 0) k.options_.mergeDistance = 1e-9 * diagonal;

  std::vector<Point3> centred(points.size());
  for (size_t i = 0; i < points.size(); ++i) centred[i] = k.modelCoordinates(points.coords[i]);

  // Merge samples closer than mergeDistance into their average (values and positions).
  const KdTree all(centred);
  std::vector<char> taken(points.size(), 0);
  std::vector<Neighbour> close;
  for (size_t i = 0; i < points.size(); ++i) {
    if (taken[i]) continue;
    all.nearest(centred[i], 64, k.options_.mergeDistance, close);
    Point3 sum{0, 0, 0};
    double valueSum = 0, driftSum = 0, vmin = INFINITY, vmax = -INFINITY;
    size_t count = 0;
    for (const Neighbour& n : close) {
      if (taken[n.index]) continue;
      taken[n.index] = 1;
      for (int a = 0; a < 3; ++a) sum[a] += centred[n.index][a];
      valueSum += points.values[n.index];
      if (options.externalDrift) driftSum += points.drift[n.index];
      vmin = std::min(vmin, points.values[n.index]);
      vmax = std::max(vmax, points.values[n.index]);
      ++count;
    }
    if (count == 0) {  // i lies farther than 64 coincident points away; keep it alone
      taken[i] = 1;
      k.coords_.push_back(centred[i]);
      k.values_.push_back(points.values[i]);
      if (options.externalDrift) k.externalDrift_.push_back(points.drift[i]);
      continue;
    }
    k.merged_ += count - 1;
    if (count > 1) k.mergedSpread_ = std::max(k.mergedSpread_, vmax - vmin);
    for (int a = 0; a < 3; ++a) sum[a] /= static_cast<double>(count);
    k.coords_.push_back(sum);
    k.values_.push_back(valueSum / static_cast<double>(count));
    if (options.externalDrift) k.externalDrift_.push_back(driftSum / static_cast<double>(count));
  }
  k.dataMean_ = std::accumulate(k.values_.begin(), k.values_.end(), 0.0) /
                static_cast<double>(k.values_.size());
  if (options.kind == KrigingKind::kSimple) k.dataMean_ = options.simpleMean;
  k.tree_ = std::make_shared<KdTree>(k.coords_);
  // Drift terms of order 1 whatever the coordinates and the external variable (drift.h).
  k.basis_.kind = options.drift;
  k.basis_.dimension = points.dimension;
  k.basis_.constant = options.kind == KrigingKind::kOrdinary;
  k.basis_.external = options.externalDrift;
  double extent = 0;
  for (const Point3& c : k.coords_)
    for (int a = 0; a < points.dimension; ++a) extent = std::max(extent, std::fabs(c[a]));
  k.basis_.coordinateScale = extent > 0 ? extent : 1.0;
  if (options.externalDrift) {
    const double n = static_cast<double>(k.externalDrift_.size());
    double mean = 0, variance = 0;
    for (double e : k.externalDrift_) {
      if (!std::isfinite(e))
        return makeError(ErrorCode::kNonFinite, "kriging: a sample's external drift is not finite");
      mean += e / n;
    }
    for (double e : k.externalDrift_) variance += (e - mean) * (e - mean) / n;
    k.basis_.externalMean = mean;
    k.basis_.externalScale = variance > 0 ? std::sqrt(variance) : 1.0;
  }
  return k;
}

Status Kriger::solveSystem(KrigingWorkspace& ws, size_t n) const {
  ws.matrix.resize(n * n);
  for (size_t i = 0; i < n; ++i) {
    const Point3& pi = coords_[ws.key[i]];
    ws.matrix[i * n + i] = variogram_.sill();
    for (size_t j = 0; j < i; ++j) {
      const double c = variogram_.covariance(std::max(distance(pi, coords_[ws.key[j]]), 1e-300));
      ws.matrix[i * n + j] = c;
      ws.matrix[j * n + i] = c;
    }
  }
  const double sill = variogram_.sill();
  double jitter = 0;
  for (;;) {
    if (ws.factor.factor(ws.matrix, n, jitter)) {
      const double condition = ws.factor.conditionEstimate();
      if (condition <= options_.maxCondition) {
        ws.cachedCondition = condition;
        ws.cachedJitter = jitter;
        break;
      }
    }
    jitter = jitter == 0 ? kFirstJitter * sill : jitter * 10;
    if (jitter > kLastJitter * sill * 1.0000001)
      return singularSystemError(n, options_.maxCondition);
  }
  // C^-1 F and the drift's system G = F^T C^-1 F, once per neighbour set.
  const size_t p = basis_.terms();
  ws.driftSolved.resize(n * p);
  ws.driftRhs.resize(p);
  for (size_t i = 0; i < n; ++i) {
    sampleDriftTerms(ws.key[i], ws.driftRhs.data());
    for (size_t j = 0; j < p; ++j) ws.driftSolved[j * n + i] = ws.driftRhs[j];
  }
  // G = (L^-1 F)^T (L^-1 F) from L^-1 F; the solve then finishes to C^-1 F.
  for (size_t j = 0; j < p; ++j) ws.factor.solveLower(&ws.driftSolved[j * n]);
  ws.drift.factor(ws.driftSolved.data(), n, n, p);
  for (size_t j = 0; j < p; ++j) ws.factor.solveUpper(&ws.driftSolved[j * n]);
  ws.cachedKey = ws.key;
  ws.cacheValid = true;
  ++ws.systemsFactored;
  return Status::ok();
}

Result<Prediction> Kriger::predict(const Point3& p, KrigingWorkspace& ws, int64_t exclude,
                                   double externalDrift) const {
  const Point3 q = modelCoordinates(p);
  const bool global = isGlobal();
  if (global && coords_.size() > kMaxSystemSize)
    return makeError(ErrorCode::kTooLarge,
                     "kriging: point by point (cross-validation), global "
                     "kriging of ",
                     coords_.size(),
                     " samples needs a dense system per point "
                     "(limit ",
                     kMaxSystemSize, "); use --neighbours 16..256");
  const size_t k = global ? coords_.size() : options_.maxNeighbours + 1 + (exclude >= 0 ? 1 : 0);
  tree_->nearest(q, k, options_.maxDistance, ws.neighbours);
  if (exclude >= 0)
    std::erase_if(ws.neighbours, [&](const Neighbour& n) { return n.index == exclude; });
  Prediction out;
  if (!global && ws.neighbours.size() > options_.maxNeighbours) {
    const double kth = ws.neighbours[options_.maxNeighbours - 1].distance;
    out.tieAtCutoff =
        ws.neighbours[options_.maxNeighbours].distance - kth <= 1e-12 * std::max(kth, 1.0);
    ws.neighbours.resize(options_.maxNeighbours);
  }
  const size_t n = ws.neighbours.size();
  out.neighbours = static_cast<uint32_t>(n);
  if (n == 0) {
    if (options_.kind == KrigingKind::kSimple) {  // no data: the known mean and the full sill
      out.value = options_.simpleMean;
      out.variance = variogram_.sill();
      out.hasData = true;
    }
    return out;
  }
  ws.key.resize(n);
  for (size_t i = 0; i < n; ++i) ws.key[i] = ws.neighbours[i].index;
  std::sort(ws.key.begin(), ws.key.end());
  if (ws.cacheValid && ws.key == ws.cachedKey) {
    ++ws.systemsReused;
  } else {
    VOXLINK_RETURN_IF_ERROR(solveSystem(ws, n));
  }
  ws.rhs.resize(n);
  for (size_t i = 0; i < n; ++i) ws.rhs[i] = variogram_.covariance(distance(q, coords_[ws.key[i]]));
  std::vector<double>& a = ws.matrix;  // reused as scratch: the factor keeps its own copy
  a.assign(ws.rhs.begin(), ws.rhs.end());
  ws.factor.solve(a.data());
  // Weights C^-1 (c - F mu) with G mu = F^T C^-1 c - f0; variance sill - w.c - mu.f0.
  const size_t terms = basis_.terms();
  std::vector<double>& mu = ws.driftRhs;
  std::vector<double> f0(terms);
  basis_.at(q, externalDrift, f0.data());
  mu.resize(terms);
  for (size_t j = 0; j < terms; ++j) {
    double s = -f0[j];
    for (size_t i = 0; i < n; ++i) s += ws.driftSolved[j * n + i] * ws.rhs[i];
    mu[j] = s;
  }
  ws.drift.solve(mu.data());
  double estimate = dataMean_, variance = variogram_.sill();
  ws.weights.resize(n);
  for (size_t i = 0; i < n; ++i) {
    double w = a[i];
    for (size_t j = 0; j < terms; ++j) w -= mu[j] * ws.driftSolved[j * n + i];
    ws.weights[i] = w;
    estimate += w * (values_[ws.key[i]] - dataMean_);
    variance -= w * ws.rhs[i];
  }
  for (size_t j = 0; j < terms; ++j) variance -= mu[j] * f0[j];
  out.driftTermsDropped = static_cast<uint32_t>(ws.drift.dropped());
  // Rounding can leave -1e-16 * sill where the variance is 0 (at a sample).
  out.value = estimate;
  out.variance = std::max(variance, 0.0);
  out.condition = ws.cachedCondition;
  out.jitter = ws.cachedJitter;
  out.hasData = true;
  if (!std::isfinite(out.value) || !std::isfinite(out.variance))
    return makeError(ErrorCode::kNonFinite, "kriging: non-finite prediction at (", p[0], ", ", p[1],
                     ", ", p[2], ") from ", n, " samples");
  return out;
}

}  // namespace voxlink::geostat
