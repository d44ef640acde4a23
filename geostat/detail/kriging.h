// SPDX-License-Identifier: BSD-3-Clause
// Ordinary, simple and universal kriging (drift.h) of scattered samples: one prediction and its
// kriging variance per location, from all samples (global) or the k nearest within a radius
// (local).
//
// Numerical safeguards, each reported rather than hidden:
//  - coordinates are centred on the data's bounding box, so UTM-sized coordinates (1e6) lose
//    no digits in distance computations;
//  - samples closer than mergeDistance are merged (values averaged), since coincident samples
//    make the covariance matrix exactly singular;
//  - each system is solved by Cholesky with a 1-norm condition estimate; when it fails or the
//    condition exceeds maxCondition, a diagonal jitter (a micro-nugget, sill * 1e-12, growing
//    tenfold up to sill * 1e-4) is added and the largest jitter used is reported; beyond that
//    the prediction is refused with a message.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "geostat/cholesky.h"
#include "geostat/detail/drift.h"
#include "geostat/detail/kd_tree.h"
#include "geostat/detail/variogram.h"
#include "geostat/point_set.h"

namespace voxlink::geostat {

enum class KrigingKind { kOrdinary, kSimple };

// The diagonal jitter ladder every solver climbs when a system is singular or too badly
// conditioned: sill * kFirstJitter, growing tenfold up to sill * kLastJitter.
inline constexpr double kFirstJitter = 1e-12;
inline constexpr double kLastJitter = 1e-4;
// The refusal once the ladder is exhausted.
Error singularSystemError(size_t n, double maxCondition);

struct KrigingOptions {
  KrigingKind kind = KrigingKind::kOrdinary;
  double simpleMean = 0.0;   // known mean for simple kriging
  size_t maxNeighbours = 0;  // 0: all samples (global kriging)
  double maxDistance = INFINITY;
  double mergeDistance = -1.0;  // < 0: 1e-9 times the bounding-box diagonal
  double maxCondition = 1e12;
  // Geometric anisotropy in the x-y plane (gstat's anis = c(angle, ratio)): the variogram's
  // range holds along the direction `anisotropyAngle` degrees clockwise from +y, and
  // anisotropyRatio (0 < r <= 1) times it across. Distances are measured after rotating that
  // direction onto an axis and stretching the other by 1 / ratio; z is left alone.
  double anisotropyAngle = 0;
  double anisotropyRatio = 1;
  // Universal kriging (drift.h): a polynomial trend in the coordinates, and/or an external
  // drift taken from PointSet::drift at the samples (and given per node at prediction).
  DriftKind drift = DriftKind::kNone;
  bool externalDrift = false;
};

struct Prediction {
  double value = NAN;
  double variance = NAN;
  uint32_t neighbours = 0;
  double condition = 0;  // 1-norm condition estimate of the covariance matrix (0: no system)
  double jitter = 0;     // diagonal regularization that was needed
  bool hasData = false;  // false: no sample in reach (ordinary kriging cannot predict)
  // Local search only: the k-th and (k+1)-th nearest samples are equally far, so another
  // implementation may legitimately pick a different neighbour set.
  bool tieAtCutoff = false;
  uint32_t driftTermsDropped = 0;  // dependent drift terms left out of this system (drift.h)
};

// Per-thread scratch space and the cached factorization of the last neighbour set.
struct KrigingWorkspace {
  std::vector<Neighbour> neighbours;
  std::vector<uint32_t> key, cachedKey;
  std::vector<double> matrix, rhs;
  std::vector<double> driftSolved;  // C^-1 F, column-major n x p
  std::vector<double> driftRhs;     // F^T C^-1 c - f0, then the Lagrange multipliers
  DriftSystem drift;
  std::vector<double> weights;  // of the last prediction, in the order of `key`
  Cholesky factor;
  double cachedCondition = 0, cachedJitter = 0;
  bool cacheValid = false;
  uint64_t systemsFactored = 0, systemsReused = 0;
};

class Kriger {
 public:
  static Result<Kriger> make(const PointSet& points, const Variogram& variogram,
                             const KrigingOptions& options);

  // Prediction at p (in the input's coordinates). `exclude` leaves one sample out
  // (cross-validation). `externalDrift`: the external drift's value at p (with
  // options().externalDrift).
  Result<Prediction> predict(const Point3& p, KrigingWorkspace& ws, int64_t exclude = -1,
                             double externalDrift = NAN) const;

  size_t sampleCount() const { return values_.size(); }
  // Sample i after merging, in the input's coordinates, and its value.
  Point3 sample(size_t i) const;
  double sampleValue(size_t i) const { return values_[i]; }
  // Sample i's external drift value (NaN without an external drift).
  double sampleExternalDrift(size_t i) const {
    return externalDrift_.empty() ? NAN : externalDrift_[i];
  }
  // The drift terms (1 for ordinary, 0 for simple kriging) and their values at sample i.
  const DriftBasis& driftBasis() const { return basis_; }
  void sampleDriftTerms(size_t i, double* f) const {
    basis_.at(coords_[i], sampleExternalDrift(i), f);
  }
  size_t mergedSamples() const { return merged_; }
  double largestMergedSpread() const { return mergedSpread_; }
  const Variogram& variogram() const { return variogram_; }
  const KrigingOptions& options() const { return options_; }
  Point3 centre() const { return centre_; }
  // What the grid solvers (global_kriging.cpp, local_kriging.cpp) work on: the samples centred
  // on centre(), their values, the mean the values are kriged around, the search tree.
  // Samples and nodes in model space: centred on centre(), and with anisotropy rotated and
  // stretched so the variogram is isotropic there.
  const std::vector<Point3>& centredSamples() const { return coords_; }
  Point3 modelCoordinates(const Point3& p) const;
  const std::vector<double>& values() const { return values_; }
  double dataMean() const { return dataMean_; }
  const KdTree& tree() const { return *tree_; }
  // All samples in every system (no --neighbours, or more neighbours than samples).
  bool isGlobal() const {
    return options_.maxNeighbours == 0 || options_.maxNeighbours >= coords_.size();
  }

 private:
  Kriger(const Variogram& v) : variogram_(v) {}
  Status solveSystem(KrigingWorkspace& ws, size_t n) const;

  Variogram variogram_;
  KrigingOptions options_;
  Point3 centre_{0, 0, 0};
  bool anisotropic_ = false;
  double cosine_ = 1, sine_ = 0;  // of the anisotropy angle
  std::vector<Point3> coords_;    // centred
  std::vector<double> values_;
  std::vector<double> externalDrift_;  // per sample, raw (empty without an external drift)
  DriftBasis basis_;
  double dataMean_ = 0;  // values are kriged as residuals from it for precision
  size_t merged_ = 0;
  double mergedSpread_ = 0;
  std::shared_ptr<KdTree> tree_;
};

}  // namespace voxlink::geostat
