// SPDX-License-Identifier: BSD-3-Clause
// How the ranks of one conversion put their parts together (converter.cpp, docs/scale.md). Each
// rank counts and encodes a contiguous share of the brick layers; prefix sums over the ranks
// place its bricks and voxels in the file, and rank 0 writes what spans every rank (BOCC, BRNK,
// META, the header and the section table). With one rank every step is the identity.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "base/rank_group.h"
#include "convert/detail/brick_count_pass.h"
#include "convert/detail/encode_output.h"
#include "format/file_writer.h"

namespace voxlink::convert {

// What pass 1 learns about this rank's brick layers [layerBegin, layerEnd).
struct BrickCensus {
  std::vector<uint16_t> counts;     // per brick of this rank's layers
  std::vector<uint32_t> occupancy;  // BOCC words [occupancyWord0, ...) over this rank's bricks
  uint64_t occupancyWord0 = 0;
  std::vector<uint32_t> voxelBase;          // BVOX of this rank's occupied bricks, + the next base
  std::vector<uint64_t> firstOccupied;      // per row of bricks of this rank: its occupied before
  uint64_t voxels = 0, occupied = 0;        // this rank's
  uint64_t firstVoxel = 0, firstBrick = 0;  // file numbers of this rank's first voxel and brick
  uint64_t totalVoxels = 0, totalOccupied = 0;
  double keptMin = INFINITY, keptMax = -INFINITY;  // this rank's, then every rank's
  double keptMinMagnitude = INFINITY;  // smallest nonzero |value| kept (f64 sources only), likewise
};

// The brick layers [first, second) rank `rank` of `size` converts.
struct LayerShare {
  uint32_t begin = 0, end = 0;
};
LayerShare layerShare(uint32_t layers, int rank, int size);

// Collective: sets totals, this rank's first voxel and brick, and the kept range of all ranks.
void exchangeCounts(base::RankGroup& ranks, BrickCensus& census);

// Numbers this rank's occupied bricks: occupancy bits, firstOccupied and voxelBase.
// `brickBegin` is the grid index of this rank's first brick.
void numberBricks(BrickCensus& census, const GridShape& shape, uint64_t brickBegin);

// Collective: BOCC of the whole grid (`words` words) on rank 0, empty elsewhere.
std::vector<uint32_t> gatherOccupancy(base::RankGroup& ranks, BrickCensus& census, uint64_t words);

// Collective: every rank's encode statistics combined (sums, minima, maxima), on every rank.
EncodeStats reduceStats(base::RankGroup& ranks, const EncodeStats& mine);

// Collective: the section parts of every other rank's writer, on rank 0 (empty elsewhere).
std::vector<format::FileWriter::SectionPart> gatherSectionParts(base::RankGroup& ranks,
                                                                const format::FileWriter& writer);

// Collective: rank 0 creates the output's temporary, the others open it (one rank: an unnamed
// temporary, as always). Fails on every rank when any rank fails.
Result<format::FileWriter> openSharedWriter(base::RankGroup& ranks, const std::string& path,
                                            const format::FileHeader& header);

}  // namespace voxlink::convert
