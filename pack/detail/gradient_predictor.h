// SPDX-License-Identifier: BSD-3-Clause
// Predicts the gradient codes of a file (a volume, or a scene's volume samples) from what the
// file stores besides them: the voxels' positions and values. The converter computed each
// gradient from the source by central differences (docs/format.md, "Gradients"); where both
// neighbours along an axis are stored, the same differences of the stored values give the same
// direction, so the prediction is exact for most voxels of a thresholded CT (99.4 % of the
// interior voxels of the 1024^3 foot). Packed files (pack/packed_file.h) store the difference
// between the real codes and this prediction, which compresses about 6x better than the codes.
//
// The prediction must be the same on every machine, or a file packed on one would unpack wrong
// on another. So it uses IEEE basic operations only (no FMA contraction: the files are built
// with -ffp-contract=off). kExact decides the code by comparisons against boundary tables
// evaluated at compile time (the converter's vectorized encoder only supplies a starting guess);
// kPortable encodes float differences with portableGradientCodes.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "format/voxlink_file.h"

namespace voxlink::pack {

using format::VoxLinkFile;

// The code whose polar cell holds the direction of (x, y, z) by exact comparisons against the
// tables below; `guess` (any code, e.g. from encodeGradients) only sets where the search starts.
// Zero or non-finite input gives kZeroGradient.
uint16_t exactGradientCode(double x, double y, double z, uint16_t guess);

// The boundary tables: cos((j + 0.5) pi / 254) for the polar index, and the azimuth boundary
// directions (cos, sin)((j + 0.5) pi / 128) of the upper half plane. Exposed for tests.
std::span<const double> polarBoundaryCosines();
std::span<const double> azimuthBoundaryCosines();
std::span<const double> azimuthBoundarySines();

// How the prediction computes: part of the packed format (each is its own GRAD codec).
enum class GradientPrediction : uint8_t {
  // Float64 differences, the code by exact comparisons against the boundary tables above
  // (codec "predicted+zstd", files packed before the portable one existed).
  kExact,
  // Float differences, the code by portableGradientCodes (codec "predicted-f32+zstd"): about
  // 4x faster and as close to the converter's codes (docs/benchmarks.md, "Packed files").
  kPortable,
};

// Fills `codes` (one entry per GRAD entry: voxelCount in a volume file, volumeVoxelCount in a
// scene) with the predicted code of every volume sample, in file order. The file must be
// structurally valid (validateStructure); GRAD is not read. A neighbour without a volume sample
// (removed by the threshold, or a scene voxel holding only geometry) is taken to be one value
// step below the smallest stored value (what a threshold removed). Runs on `threads` threads
// (0: all cores).
void predictGradientCodes(const VoxLinkFile& file, std::span<uint16_t> codes,
                          GradientPrediction kind, unsigned threads = 0);

// Adds (mod 2^16) each predicted code to the entry of `codes` that it belongs to: a packed
// file's GRAD residuals become the codes in place, without a buffer of predictions.
void addPredictedGradientCodes(const VoxLinkFile& file, std::span<uint16_t> codes,
                               GradientPrediction kind, unsigned threads = 0);

// The codes of predictGradientCodes a range of GRAD entries at a time, from any number of
// threads at once: packing predicts each chunk of GRAD just before it compresses it, instead of
// the whole section into a buffer as large as GRAD. Each call predicts the bricks that the
// range meets, whole (about two bricks' voxels more than the range).
class GradientRangePredictor {
 public:
  GradientRangePredictor(const VoxLinkFile& file, GradientPrediction kind);
  ~GradientRangePredictor();
  // out[j] = the predicted code of GRAD entry first + j (0 for entries past the last sample).
  void predict(uint64_t first, std::span<uint16_t> out) const;

  class Impl;

 private:
  std::unique_ptr<const Impl> impl_;
};

// The same codes, one voxel at a time: without the eight-cell kernels that predictGradientCodes
// uses for a volume's bricks away from its faces where the CPU has them
// (pack/detail/dense_brick_rows.h). The reference that tests hold those kernels to.
void predictGradientCodesPerVoxel(const VoxLinkFile& file, std::span<uint16_t> codes,
                                  GradientPrediction kind, unsigned threads = 0);

}  // namespace voxlink::pack
