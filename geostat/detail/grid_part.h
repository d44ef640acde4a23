// SPDX-License-Identifier: BSD-3-Clause
// One share of a grid's nodes among several processes (the ranks of an MPI job,
// docs/scale.md). The work units of the one-process order (local kriging: rows of bricks of a
// slab; global kriging: blocks of nodes; random fields: rows of FFT blocks) are numbered in file
// order, and share `index` of `count` takes units [U index / count, U (index + 1) / count). The
// split depends only on the count, and every node is computed exactly as one process computes
// it, so the shares together are byte for byte the one-process grid.
#pragma once

#include <array>
#include <cstdint>
#include <functional>

#include "base/error.h"

namespace voxlink::geostat {

struct GridPart {
  uint32_t index = 0, count = 1;  // this share, of `count` (1: the whole grid)

  uint64_t firstUnit(uint64_t units) const { return units * index / count; }
  uint64_t endUnit(uint64_t units) const { return units * (index + 1) / count; }
};

// Receives finished nodes [firstNode, firstNode + nodes) of the whole grid, in file order (x
// fastest, then y, then z): their values and, for kriging, variances (else null).
using NodeRunSink = std::function<Status(uint64_t firstNode, uint64_t nodes, const double* values,
                                         const double* variances)>;

// The rows [y0, y1) of slices [z0, z0 + slices), held in a buffer of those rows slice after
// slice, as runs of consecutive nodes of the grid: one run when the rows are whole slices, else
// one per slice. `run` gets the first node in the grid and the offset of the run in the buffer.
Status forEachRowRun(
    const std::array<uint32_t, 3>& dims, uint32_t z0, uint32_t slices, uint32_t y0, uint32_t y1,
    const std::function<Status(uint64_t firstNode, uint64_t nodes, uint64_t offset)>& run);

}  // namespace voxlink::geostat
