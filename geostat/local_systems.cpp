// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/local_systems.h"

#include <algorithm>
#include <cmath>

#include "geostat/detail/spd_kernels.h"

namespace voxlink::geostat {

using spd::batch::kLanes;

LocalSystems::LocalSystems(const Kriger& kriger)
    : kriger_(kriger),
      terms_(kriger.driftBasis().terms()),
      sill_(kriger.variogram().sill()),
      nugget_(kriger.variogram().params().nugget),
      maxCondition_(kriger.options().maxCondition) {}

void LocalSystems::loadCandidates(ThreadState& ts) const {
  const size_t m = ts.candidates.size();
  const auto& coords = kriger_.centredSamples();
  ts.cx.resize(m);
  ts.cy.resize(m);
  ts.cz.resize(m);
  for (size_t i = 0; i < m; ++i) {
    const Point3& p = coords[ts.candidates[i]];
    ts.cx[i] = p[0];
    ts.cy[i] = p[1];
    ts.cz[i] = p[2];
  }
  // Filled on first use (NaN: not yet): in 3-D most nodes have their own neighbour set,
  // and all pairs of a crowded brick cost more exp() calls than its nodes ever read.
  ts.pair.assign(m * m, NAN);
}

// The covariances among the samples of f.key (lower triangle, column-major, leading dimension
// ld) plus jitter on the diagonal, computed as queue() computes them (the same
// bits); returns the 1-norm of that matrix.
double LocalSystems::gather(ThreadState& ts, const std::vector<uint32_t>& key, double jitter,
                            double* a, size_t ld) const {
  const size_t n = key.size();
  const auto& coords = kriger_.centredSamples();
  ts.work.assign(n, 0.0);  // column sums of |A|
  for (size_t j = 0; j < n; ++j) {
    double* column = a + j * ld;
    column[j] = sill_ + jitter;
    double sum = sill_ + jitter;
    const Point3& p = coords[key[j]];
    for (size_t i = j + 1; i < n; ++i) {  // the upper part is never read
      const Point3& q = coords[key[i]];
      const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
      const double c =
          kriger_.variogram().covariance(std::max(std::sqrt(dx * dx + dy * dy + dz * dz), 1e-300));
      column[i] = c;
      sum += std::fabs(c);
      ts.work[i] += std::fabs(c);
    }
    ts.work[j] += sum;
  }
  return *std::max_element(ts.work.begin(), ts.work.end());
}

// One system alone: the first attempt, then jitter growing tenfold while the condition exceeds
// --max-condition (docs/kriging.md, "Numerical safeguards").
Status LocalSystems::factor(ThreadState& ts, Factorization& f) const {
  const size_t n = f.key.size(), ld = spd::paddedSize(n);
  double jitter = 0;
  f.l.resize(ld * n);
  for (;;) {
    const double norm1 = gather(ts, f.key, jitter, f.l.data(), ld);
    // With a nugget the matrix is nugget I plus a positive semidefinite one, so its smallest
    // eigenvalue is >= nugget and cond_1 <= sqrt(n) ||A||_1 / nugget (doubled for rounding):
    // below --max-condition that bound makes the estimate (10 triangular solves) needless.
    double bound = nugget_ > 0 ? 2 * std::sqrt(double(n)) * norm1 / nugget_ : INFINITY;
    if (spd::factorLower(f.l.data(), n, ld)) {
      f.bounded = jitter == 0 && bound <= maxCondition_;
      // Without a nugget, ||A^-1||_1 <= a bound from L^-1 (a third of the estimate's cost,
      // at most n^1.5 x the true norm) settles most systems as the estimate would.
      if (!f.bounded && jitter == 0) {
        ts.work.resize(n * (n + 1));
        double inverseBound =
            2 * norm1 * spd::inverseNormComparisonBound(f.l.data(), n, ld, ts.work.data());
        if (!(inverseBound <= maxCondition_))
          inverseBound = 2 * norm1 * spd::inverseNormBound(f.l.data(), n, ld, ts.work.data());
        if (inverseBound <= maxCondition_) f.bounded = true, bound = inverseBound;
      }
      if (!f.bounded) ts.work.resize(3 * n);
      f.condition =
          f.bounded ? bound : norm1 * spd::inverseNormEstimate(f.l.data(), n, ld, ts.work.data());
      if (f.condition <= maxCondition_) break;
    }
    jitter = jitter == 0 ? kFirstJitter * sill_ : jitter * 10;
    if (jitter > kLastJitter * sill_ * 1.0000001) return singularSystemError(n, maxCondition_);
  }
  f.jitter = jitter;
  finish(ts, f);
  return Status::ok();
}

// U = L^-1 F, r = L^-1 (z - mean), G = U^T U and U^T r from the factor in f.l.
void LocalSystems::finish(ThreadState& ts, Factorization& f) const {
  const size_t n = f.key.size(), ld = spd::paddedSize(n);
  const double mean = kriger_.dataMean();
  const size_t p = terms_;
  f.u.resize(n * p);
  ts.drift.resize(p);
  for (size_t i = 0; i < n; ++i) {
    kriger_.sampleDriftTerms(f.key[i], ts.drift.data());
    for (size_t j = 0; j < p; ++j) f.u[j * n + i] = ts.drift[j];
  }
  f.r.resize(n);
  for (size_t i = 0; i < n; ++i) f.r[i] = kriger_.values()[f.key[i]] - mean;
  if (p > 0)
    spd::solveLower(f.l.data(), n, ld, f.u.data(), f.r.data());
  else
    spd::solveLower(f.l.data(), n, ld, f.r.data());
  for (size_t j = 1; j < p; ++j) spd::solveLower(f.l.data(), n, ld, &f.u[j * n]);
  f.drift.factor(f.u.data(), n, n, p);
  f.ur.resize(p);
  for (size_t j = 0; j < p; ++j) f.ur[j] = spd::dot(&f.u[j * n], f.r.data(), n);
  f.pending = false;
}

// Queues the system of ts.picked in lane ts.queuedCount. One pass copies its pair covariances
// from the brick's cache and lists those not evaluated yet (branch-free: about a third of them
// are new, at random); those are then evaluated together, the exponential model's exp() four at
// a time, with gather()'s operations (the same bits), and stored in both places.
void LocalSystems::queue(ThreadState& ts, Factorization& f) const {
  f.pending = true;
  const size_t lane = ts.queuedCount++, n = ts.picked.size(), m = ts.candidates.size();
  ts.queued[lane] = &f;
  ts.compact.resize(n * n * kLanes);
  ts.missing.resize(n * (n - 1) / 2);
  size_t count = 0;
  // Pointers held in registers: through the vectors every store reloaded them (the stores may
  // alias a vector's pointer).
  const uint32_t* picked = ts.picked.data();
  auto* __restrict missing = ts.missing.data();
  for (size_t j = 0; j < n; ++j) {
    double* __restrict column = &ts.compact[spd::batch::at(0, j, n, lane)];
    const double* pairs = &ts.pair[size_t{picked[j]} * m];
    column[j * kLanes] = sill_;
    for (size_t i = j + 1; i < n; ++i) {
      const double c = pairs[picked[i]];
      column[i * kLanes] = c;
      missing[count] = uint32_t(i | j << 16);  // one store per pair
      count += std::isnan(c);
    }
  }
  ts.missingDistance.resize(count);
  for (size_t k = 0; k < count; ++k) {
    const uint32_t b = ts.picked[ts.missing[k] >> 16], a = ts.picked[ts.missing[k] & 0xffff];
    const double dx = ts.cx[b] - ts.cx[a], dy = ts.cy[b] - ts.cy[a], dz = ts.cz[b] - ts.cz[a];
    ts.missingDistance[k] = std::max(std::sqrt(dx * dx + dy * dy + dz * dz), 1e-300);
  }
  ts.missingCovariance.resize(count);
  kriger_.variogram().covariances(ts.missingDistance.data(), ts.missingCovariance.data(), count);
  for (size_t k = 0; k < count; ++k) {
    const uint32_t i = ts.missing[k] & 0xffff, j = ts.missing[k] >> 16;
    const double c = ts.missingCovariance[k];
    const uint32_t a = ts.picked[i], b = ts.picked[j];
    ts.compact[spd::batch::at(i, j, n, lane)] = ts.pair[size_t{b} * m + a] =
        ts.pair[size_t{a} * m + b] = c;
  }
}

// The first attempt of factor() on `count` (> 0) queued systems at once; done[lane] where it
// settled the system as factor() would have.
void LocalSystems::flushLanes(ThreadState& ts, size_t count, std::array<bool, kLanes>& done) const {
  const size_t n = ts.queued[0]->key.size();
  for (size_t lane = count; lane < kLanes; ++lane)  // an idle lane factors the identity
    for (size_t j = 0; j < n; ++j)
      for (size_t i = j; i < n; ++i) ts.compact[spd::batch::at(i, j, n, lane)] = i == j;
  // gather()'s norm bits, four lanes at a time (one chain of dependent adds per column each).
  ts.work.resize(2 * n * kLanes);
  double norms[kLanes];
  spd::batch::norm1(ts.compact.data(), n, ts.work.data(), norms);
  uint8_t ok[kLanes];
  spd::batch::factorLower(ts.compact.data(), n, ok);
  // The factors out of the batch, four rows of all lanes at a time.
  const size_t ld = spd::paddedSize(n);
  double* factors[kLanes];
  for (size_t lane = 0; lane < count; ++lane) {
    ts.queued[lane]->l.resize(ld * n);
    factors[lane] = ts.queued[lane]->l.data();
  }
  spd::batch::unpackLower(ts.compact.data(), n, count, factors, ld);
  // factor()'s first attempt from here on: the nugget's bound, else the comparison bound,
  // computed for all lanes at once when any lane needs it.
  std::array<double, kLanes> bounds;
  bool needComparison = false;
  for (size_t lane = 0; lane < count; ++lane) {
    bounds[lane] = nugget_ > 0 ? 2 * std::sqrt(double(n)) * norms[lane] / nugget_ : INFINITY;
    needComparison |= ok[lane] && !(bounds[lane] <= maxCondition_);
  }
  if (needComparison) {
    double comparison[kLanes];
    spd::batch::inverseNormComparisonBound(ts.compact.data(), n, ts.work.data(), comparison);
    for (size_t lane = 0; lane < count; ++lane)
      if (!(bounds[lane] <= maxCondition_)) bounds[lane] = 2 * norms[lane] * comparison[lane];
  }
  for (size_t lane = 0; lane < count; ++lane) {
    done[lane] = false;
    // factor() takes it further.
    if (!ok[lane] || !(bounds[lane] <= maxCondition_)) continue;
    Factorization& f = *ts.queued[lane];
    const double bound = bounds[lane];
    f.bounded = true;
    f.condition = bound;
    f.jitter = 0;
    finish(ts, f);
    done[lane] = true;
  }
}

Status LocalSystems::flush(ThreadState& ts) const {
  const size_t count = ts.queuedCount;
  ts.queuedCount = 0;
  std::array<bool, kLanes> done{};
  // Even a part-filled batch: its systems are gathered already, and factor() would gather
  // them again without the brick's pair cache.
  if (count > 0) flushLanes(ts, count, done);
  for (size_t lane = 0; lane < count; ++lane) {
    Factorization& f = *ts.queued[lane];
    if (!done[lane]) VOXLINK_RETURN_IF_ERROR(factor(ts, f));
    if (f.bounded) ++ts.summary.systemsBounded;
  }
  return Status::ok();
}

}  // namespace voxlink::geostat
