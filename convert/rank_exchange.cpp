// SPDX-License-Identifier: BSD-3-Clause
#include "convert/detail/rank_exchange.h"

#include <algorithm>
#include <cstring>

namespace voxlink::convert {

LayerShare layerShare(uint32_t layers, int rank, int size) {
  const auto at = [&](int r) {
    return static_cast<uint32_t>(uint64_t{layers} * static_cast<uint64_t>(r) /
                                 static_cast<uint64_t>(size));
  };
  return LayerShare{at(rank), at(rank + 1)};
}

void exchangeCounts(base::RankGroup& ranks, BrickCensus& census) {
  struct Counts {
    uint64_t voxels, occupied;
    double keptMin, keptMax, keptMinMagnitude;
  };
  const Counts mine{census.voxels, census.occupied, census.keptMin, census.keptMax,
                    census.keptMinMagnitude};
  std::vector<Counts> all(static_cast<size_t>(ranks.size()));
  ranks.allGather(&mine, sizeof mine, all.data());
  census.firstVoxel = census.firstBrick = census.totalVoxels = census.totalOccupied = 0;
  for (int r = 0; r < ranks.size(); ++r) {
    const Counts& c = all[static_cast<size_t>(r)];
    if (r < ranks.rank()) census.firstVoxel += c.voxels, census.firstBrick += c.occupied;
    census.totalVoxels += c.voxels;
    census.totalOccupied += c.occupied;
    census.keptMin = std::min(census.keptMin, c.keptMin);
    census.keptMax = std::max(census.keptMax, c.keptMax);
    census.keptMinMagnitude = std::min(census.keptMinMagnitude, c.keptMinMagnitude);
  }
}

void numberBricks(BrickCensus& census, const GridShape& shape, uint64_t brickBegin) {
  const uint64_t bricks = census.counts.size();
  const uint64_t brickEnd = brickBegin + bricks;
  census.occupancyWord0 = brickBegin / 32;
  census.occupancy.assign(bricks == 0 ? 0 : (brickEnd + 31) / 32 - census.occupancyWord0, 0);
  census.firstOccupied.resize(bricks / shape.grid[0]);
  census.voxelBase.clear();
  census.voxelBase.reserve(bricks / 8 + 2);
  uint64_t occupied = 0, voxel = census.firstVoxel;
  for (uint64_t b = 0; b < bricks; ++b) {
    if (b % shape.grid[0] == 0) census.firstOccupied[b / shape.grid[0]] = occupied;
    if (census.counts[b] == 0) continue;
    const uint64_t bit = brickBegin + b - census.occupancyWord0 * 32;
    census.occupancy[bit >> 5] |= 1u << (bit & 31);
    VOXLINK_CHECK_LE(voxel, UINT32_MAX);  // the caller refused files over kMaxVoxels
    census.voxelBase.push_back(static_cast<uint32_t>(voxel));
    voxel += census.counts[b];
    ++occupied;
  }
  census.voxelBase.push_back(static_cast<uint32_t>(voxel));
}

std::vector<uint32_t> gatherOccupancy(base::RankGroup& ranks, BrickCensus& census, uint64_t words) {
  if (ranks.size() == 1) return std::move(census.occupancy);
  std::vector<uint8_t> mine(8 + census.occupancy.size() * 4);
  std::memcpy(mine.data(), &census.occupancyWord0, 8);
  std::memcpy(mine.data() + 8, census.occupancy.data(), census.occupancy.size() * 4);
  const std::vector<std::vector<uint8_t>> parts = ranks.gatherToRoot(mine);
  std::vector<uint32_t> all(ranks.rank() == 0 ? words : 0, 0);
  for (const std::vector<uint8_t>& part : parts) {  // neighbours may share a word: OR them
    uint64_t word0 = 0;
    std::memcpy(&word0, part.data(), 8);
    for (size_t i = 0; 8 + 4 * i < part.size(); ++i) {
      uint32_t w = 0;
      std::memcpy(&w, part.data() + 8 + 4 * i, 4);
      all[word0 + i] |= w;
    }
  }
  return all;
}

EncodeStats reduceStats(base::RankGroup& ranks, const EncodeStats& mine) {
  std::vector<EncodeStats> all(static_cast<size_t>(ranks.size()));
  ranks.allGather(&mine, sizeof mine, all.data());
  EncodeStats total;
  for (const EncodeStats& s : all) total.add(s);
  return total;
}

std::vector<format::FileWriter::SectionPart> gatherSectionParts(base::RankGroup& ranks,
                                                                const format::FileWriter& writer) {
  using Part = format::FileWriter::SectionPart;
  if (ranks.size() == 1) return {};
  const std::vector<Part> mine = writer.sectionParts();
  const auto* bytes = reinterpret_cast<const uint8_t*>(mine.data());
  const std::vector<std::vector<uint8_t>> parts =
      ranks.gatherToRoot({bytes, mine.size() * sizeof(Part)});
  std::vector<Part> others;
  for (size_t r = 1; r < parts.size(); ++r) {
    const size_t count = parts[r].size() / sizeof(Part);
    const size_t at = others.size();
    others.resize(at + count);
    std::memcpy(others.data() + at, parts[r].data(), count * sizeof(Part));
  }
  return others;
}

Result<format::FileWriter> openSharedWriter(base::RankGroup& ranks, const std::string& path,
                                            const format::FileHeader& header) {
  if (ranks.size() == 1) return format::FileWriter::create(path, header);
  std::optional<format::FileWriter> writer;
  Status created;
  std::string tempPath;
  if (ranks.rank() == 0) {
    auto w = format::FileWriter::createShared(path, header);
    if (w) {
      tempPath = w->tempPath();
      writer.emplace(std::move(*w));
    } else {
      created = w.status();
    }
  }
  VOXLINK_RETURN_IF_ERROR(base::agree(ranks, created));
  ranks.broadcast(tempPath, 0);
  Status attached;
  if (ranks.rank() != 0) {
    auto w = format::FileWriter::attach(path, tempPath, header);
    if (w)
      writer.emplace(std::move(*w));
    else
      attached = w.status();
  }
  VOXLINK_RETURN_IF_ERROR(base::agree(ranks, attached));  // rank 0's writer removes the temporary
  return std::move(*writer);
}

}  // namespace voxlink::convert
