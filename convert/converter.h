// SPDX-License-Identifier: BSD-3-Clause
// Dense volume -> VoxLink file, in two streamed passes over z slabs with bounded memory:
//   1. classify every voxel, count kept voxels per brick, find the kept value range;
//   2. classify again, compute central-difference gradients, encode them, write each brick's
//      rows, masks, values and gradients straight to their final place in the file.
// The output is byte-identical for any slab size, thread count and rank count.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "base/rank_group.h"
#include "convert/classification.h"
#include "format/layout.h"
#include "format/scalar_type.h"
#include "sources/volume_source.h"

namespace voxlink::convert {

using sources::OpenOptions;
using sources::VolumeSource;

struct ConvertOptions {
  uint32_t brickSize = 8;
  format::Axis axis = format::Axis::kZ;
  Classification classification;
  unsigned threads = 0;      // 0: all hardware threads
  uint32_t slabSlices = 64;  // z slices per slab; rounded up to a multiple of brickSize
  // Stored value type; empty chooses the smallest lossless type for the kept range (u8 stays u8).
  std::optional<StoredType> storedType;
  double errorBound = 0.0;  // max abs error allowed when a lossy stored type is asked for
  // How the source was opened, recorded in META so the file can be re-classified later.
  OpenOptions sourceOptions;
  const std::atomic<bool>* cancel = nullptr;  // set to stop early (kCancelled)
  std::function<void(double fraction, const char* stage)> progress;  // may be empty
  // Sampling rate of the gradient-error measurement (1 in N kept voxels is decoded and compared).
  uint32_t errorSampleStride = 64;
  // The processes converting this volume together (docs/scale.md): each classifies and encodes
  // a share of the brick layers, reading only those slices and the ghost slices around them,
  // and all write one file, byte for byte the file one process writes. Null: this one alone.
  base::RankGroup* ranks = nullptr;
};

struct ConvertSummary {
  uint64_t voxels = 0;
  uint64_t sourceVoxels = 0;
  uint64_t occupiedBricks = 0;
  uint64_t bricks = 0;
  uint64_t bytes = 0;       // output file size
  double seconds = 0;       // wall time, both passes
  double countSeconds = 0;  // pass 1
  double writeSeconds = 0;  // pass 2 + commit
  StoredType storedType = StoredType::kU8;
  double valueMaxAbsError = 0;  // introduced by the stored type, source units
  double valueMaxRelError = 0;
  double gradientMeanErrorDeg = 0;  // polar16 quantization, measured on sampled voxels
  double gradientMaxErrorDeg = 0;
  uint64_t gradientSamples = 0;
  uint64_t zeroGradients = 0;  // kept voxels whose gradient is zero
};

Result<ConvertSummary> convertVolume(VolumeSource& source, const ConvertOptions& options,
                                     const std::string& outputPath);

}  // namespace voxlink::convert
