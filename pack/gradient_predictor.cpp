// SPDX-License-Identifier: BSD-3-Clause
#include "pack/detail/gradient_predictor.h"

#include <cstdint>
#include <span>
#include <vector>

#include "base/check.h"
#include "base/parallel_for.h"
#include "base/vector_clones.h"
#include "pack/detail/brick_gradient_predictor.h"
#include "pack/detail/central_differences.h"
#include "pack/detail/gradient_boundaries.h"

namespace voxlink::pack {

using format::MaskRank;
using format::VoxLinkFile;

namespace detail {

VOXLINK_VECTOR_CLONES void centralDifferencesFloat(const float* __restrict value,
                                                   const uint32_t* __restrict cell, uint32_t count,
                                                   const uint32_t* stride, const float* half,
                                                   float* __restrict g0, float* __restrict g1,
                                                   float* __restrict g2) {
  centralDifferences<float>(value, cell, count, stride, half, g0, g1, g2);
}

}  // namespace detail

using detail::CodeWindow;
using detail::exactCode;
using detail::kAzimuthCos;
using detail::kAzimuthSin;
using detail::kPolar;
using detail::Predictor;

std::span<const double> polarBoundaryCosines() { return kPolar; }
std::span<const double> azimuthBoundaryCosines() { return kAzimuthCos; }
std::span<const double> azimuthBoundarySines() { return kAzimuthSin; }

uint16_t exactGradientCode(double x, double y, double z, uint16_t guess) {
  return exactCode(x, y, z, guess);
}

namespace {

// How a public entry point predicts: with the eight-cell kernels where they apply (else one
// voxel at a time), and adding to the output's codes or writing them.
struct PredictionMode {
  bool dense;
  bool add;
};

// Occupied bricks in file order, so workers can take ranges of them.
std::vector<uint64_t> occupiedBricks(const VoxLinkFile& file) {
  std::vector<uint64_t> bricks;
  bricks.reserve(file.occupiedBrickCount());
  const auto occupancy = file.occupancyWords();
  for (uint64_t w = 0; w < occupancy.size(); ++w)
    for (uint32_t bits = occupancy[w]; bits != 0; bits &= bits - 1)
      bricks.push_back(w * 32 + static_cast<uint64_t>(std::countr_zero(bits)));
  return bricks;
}

template <class Real>
void predictWith(const VoxLinkFile& file, std::span<uint16_t> codes, unsigned threads,
                 PredictionMode mode) {
  const Predictor<Real> predictor(file, mode.dense, mode.add);
  const std::vector<uint64_t> bricks = occupiedBricks(file);
  // Batches of bricks, each worker with its own scratch.
  constexpr uint64_t kBatch = 256;
  const uint64_t batches = (bricks.size() + kBatch - 1) / kBatch;
  const CodeWindow window{codes.data()};
  parallelFor(batches, threads, [&](uint64_t batch) {
    predictor.predictBricks(bricks, batch * kBatch,
                            std::min<uint64_t>((batch + 1) * kBatch, bricks.size()), window);
  });
}

void predictAs(GradientPrediction kind, const VoxLinkFile& file, std::span<uint16_t> codes,
               unsigned threads, PredictionMode mode) {
  VOXLINK_CHECK_EQ(codes.size(), sampleSlots(file.header()));  // one code per GRAD entry
  if (kind == GradientPrediction::kExact)
    predictWith<double>(file, codes, threads, mode);
  else
    predictWith<float>(file, codes, threads, mode);
}

}  // namespace

class GradientRangePredictor::Impl {
 public:
  virtual ~Impl() = default;
  virtual void predict(uint64_t first, std::span<uint16_t> out) const = 0;
};

namespace {

template <class Real>
class RangePrediction final : public GradientRangePredictor::Impl {
 public:
  explicit RangePrediction(const VoxLinkFile& file)
      : predictor_(file, /*allowDense=*/true, /*add=*/false),
        bricks_(occupiedBricks(file)),
        start_(bricks_.size() + 1) {
    // Each brick's first GRAD entry: its first voxel's, in a scene the VMSK slot of the first
    // volume sample at or after it.
    const auto base = file.brickVoxelBase();
    const MaskRank samples = file.isScene() ? MaskRank(file.volumeMaskWords()) : MaskRank();
    // (Kept non-decreasing whatever the file says: the searches below rely on it.)
    for (size_t k = 0; k < start_.size(); ++k) {
      const uint64_t at = k >= base.size() ? 0 : file.isScene() ? samples.slot(base[k]) : base[k];
      start_[k] = std::max(k == 0 ? 0 : start_[k - 1], at);
    }
  }

  void predict(uint64_t first, std::span<uint16_t> out) const override {
    std::fill(out.begin(), out.end(), uint16_t{0});
    if (out.empty() || bricks_.empty()) return;
    const uint64_t end = first + out.size();
    // The bricks whose entries meet [first, end), predicted whole into a window of their own.
    const auto from = std::upper_bound(start_.begin(), start_.end(), first);
    const uint64_t k0 =
        from == start_.begin() ? 0 : static_cast<uint64_t>(from - start_.begin()) - 1;
    const uint64_t k1 = std::min<uint64_t>(
        static_cast<uint64_t>(std::lower_bound(start_.begin(), start_.end(), end) - start_.begin()),
        bricks_.size());
    if (k0 >= k1) return;
    thread_local std::vector<uint16_t> codes;
    codes.assign(start_[k1] - start_[k0], 0);
    const CodeWindow window{codes.data(), start_[k0]};
    predictor_.predictBricks(bricks_, k0, k1, window);
    const uint64_t begin = std::max(first, start_[k0]), stop = std::min(end, start_[k1]);
    if (begin < stop) std::copy(window.at(begin), window.at(stop), out.data() + (begin - first));
  }

 private:
  Predictor<Real> predictor_;
  std::vector<uint64_t> bricks_;
  std::vector<uint64_t> start_;  // occupied brick k's first GRAD entry; [k + 1] ends it
};

}  // namespace

GradientRangePredictor::GradientRangePredictor(const VoxLinkFile& file, GradientPrediction kind) {
  if (kind == GradientPrediction::kExact)
    impl_ = std::make_unique<RangePrediction<double>>(file);
  else
    impl_ = std::make_unique<RangePrediction<float>>(file);
}
GradientRangePredictor::~GradientRangePredictor() = default;

void GradientRangePredictor::predict(uint64_t first, std::span<uint16_t> out) const {
  impl_->predict(first, out);
}

void predictGradientCodes(const VoxLinkFile& file, std::span<uint16_t> codes,
                          GradientPrediction kind, unsigned threads) {
  predictAs(kind, file, codes, threads, {.dense = true, .add = false});
}

void addPredictedGradientCodes(const VoxLinkFile& file, std::span<uint16_t> codes,
                               GradientPrediction kind, unsigned threads) {
  predictAs(kind, file, codes, threads, {.dense = true, .add = true});
}

void predictGradientCodesPerVoxel(const VoxLinkFile& file, std::span<uint16_t> codes,
                                  GradientPrediction kind, unsigned threads) {
  predictAs(kind, file, codes, threads, {.dense = false, .add = false});
}

}  // namespace voxlink::pack
