// SPDX-License-Identifier: BSD-3-Clause
// Unconditional stationary Gaussian random fields on large voxel grids (the paper's 512^3 and
// 1024^3 N(0,1) kriging-like volumes), generated slab by slab with bounded memory.
//
// Method: the field is white noise convolved with the covariance's lattice square root
// (grf_kernel.h), evaluated block by block with FFTs (overlap-save). The white noise at each
// lattice point is a hash of (seed, x, y, z), so the field does not depend on block size,
// thread count or slab order, and any sub-volume can be regenerated alone.
// Memory: the kernel embedding, one FFT block per thread, and one output slab of
// block-depth z slices; never the whole volume.
#pragma once

#include <array>
#include <functional>
#include <string>

#include "geostat/detail/grf_kernel.h"
#include "geostat/detail/grid_part.h"

namespace voxlink::geostat {

// Largest field extent per axis: the noise lattice packs each coordinate, which runs a kernel
// radius beyond the field, into a 21-bit part of its hash key (grf.cpp, kCoordinateBias).
inline constexpr uint32_t kMaxGrfAxis = 1u << 19;

struct GrfSpec {
  std::array<uint32_t, 3> dims{64, 64, 64};
  VariogramParams model;  // lengths in voxels; sill = variance of the field
  double mean = 0;
  uint64_t seed = 1;
  GrfKernelOptions kernel;
  uint32_t fftSize = 0;  // 0: chosen per axis for speed within maxBlockBytes
  uint64_t maxBlockBytes = uint64_t{512} << 20;  // in-place FFT buffer of one thread
  unsigned threads = 0;                          // 0: hardware concurrency
  uint64_t memoryBytes = 0;  // what the buffers may take; 0: format::memoryForThisProcess()
};

struct GrfReport {
  GrfKernel kernel;  // kernel diagnostics (octant cleared after generation)
  std::array<uint32_t, 3> fftSize{1, 1, 1};
  std::array<uint32_t, 3> blockSize{1, 1, 1};  // output voxels per block
  uint64_t blocks = 0;
  unsigned threads = 0;  // fewer than asked for when their FFT blocks do not all fit in memory
  uint64_t peakBufferBytes = 0;  // kernel embedding or FFT buffers + slab, whichever is larger
  double kernelSeconds = 0, seconds = 0;
  std::string text() const;
};

// Receives consecutive slabs [z0, z0 + count), x fastest.
using GrfSink = std::function<Status(uint32_t z0, uint32_t count, const double* slab)>;

Result<GrfReport> generateGrf(const GrfSpec& spec, const GrfSink& sink);

// The voxels of share `part` of the field (grid_part.h; the units are rows of FFT blocks),
// byte for byte as generateGrf makes them; `sink` gets no variances. Every share computes the
// kernel; `blocks` in the report counts this share's.
Result<GrfReport> generateGrfPart(const GrfSpec& spec, const GridPart& part,
                                  const NodeRunSink& sink);

// The standard normal white noise value at lattice point (x, y, z) for `seed` (coordinates may
// lie outside the grid, down to -2^20).
double latticeNoise(uint64_t seed, int64_t x, int64_t y, int64_t z);

}  // namespace voxlink::geostat
