// SPDX-License-Identifier: BSD-3-Clause
// The split of a scene build among MPI ranks (scene/detail/scene_ranks.h) and the gather that
// collects the ranks' voxels on rank 0 (base/rank_group.h), without MPI: a scripted group plays
// rank 0 of three and answers for the other two. tests/mpi runs the real thing under mpirun.
#include "scene/detail/scene_ranks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "base/rank_group.h"

namespace voxlink::scene {
namespace {

TEST(RankSlab, BrickLayersTileTheGridForEveryRankCount) {
  for (uint32_t depth : {1u, 7u, 8u, 41u, 294u, 1000u})
    for (uint32_t brick : {4u, 8u, 16u, 32u})
      for (int ranks = 1; ranks <= 9; ++ranks) {
        uint32_t next = 0;
        for (int r = 0; r < ranks; ++r) {
          const geometry::ZSlab slab = rankSlab(depth, brick, r, ranks);
          EXPECT_EQ(slab.begin, next) << depth << " " << brick << " " << r << "/" << ranks;
          EXPECT_LE(slab.begin, slab.end);
          EXPECT_TRUE(slab.begin % brick == 0 || slab.begin == depth);
          next = slab.end;
        }
        EXPECT_EQ(next, depth) << depth << " " << brick << " " << ranks;
      }
  // 10 layers on 4 ranks: 2, 3, 2, 3.
  EXPECT_EQ(rankSlab(37, 4, 1, 4).begin, 8u);
  EXPECT_EQ(rankSlab(37, 4, 1, 4).end, 20u);
  EXPECT_EQ(rankSlab(37, 4, 3, 4).end, 37u);
}

// Rank 0 of three; ranks 1 and 2 send the next `chunk` bytes of their scripted parts each round.
class ScriptedRanks final : public base::RankGroup {
 public:
  ScriptedRanks(std::vector<std::vector<uint8_t>> others, uint64_t chunk)
      : others_(std::move(others)), at_(others_.size(), 0), chunk_(chunk) {}
  int rank() const override { return 0; }
  int size() const override { return 1 + int(others_.size()); }
  void allGather(const void* mine, size_t bytes, void* all) override {  // the parts' sizes
    ASSERT_EQ(bytes, sizeof(uint64_t));
    auto* sizes = static_cast<uint64_t*>(all);
    std::memcpy(sizes, mine, bytes);
    for (size_t r = 0; r < others_.size(); ++r) sizes[r + 1] = others_[r].size();
  }
  std::vector<std::vector<uint8_t>> gatherToRoot(std::span<const uint8_t> mine) override {
    ++rounds;
    largestPart = std::max<uint64_t>(largestPart, mine.size());
    std::vector<std::vector<uint8_t>> parts = {{mine.begin(), mine.end()}};
    for (size_t r = 0; r < others_.size(); ++r) {
      const size_t n = std::min<size_t>(chunk_, others_[r].size() - at_[r]);
      parts.emplace_back(others_[r].begin() + at_[r], others_[r].begin() + at_[r] + n);
      at_[r] += n;
    }
    return parts;
  }
  void broadcast(std::string&, int) override {}
  void startQueue(uint64_t) override {}
  std::optional<uint64_t> nextItem() override { return std::nullopt; }
  void finishQueue() override {}
  int rounds = 0;
  uint64_t largestPart = 0;

 private:
  std::vector<std::vector<uint8_t>> others_;
  std::vector<size_t> at_;
  uint64_t chunk_;
};

std::vector<uint8_t> counting(size_t n, uint8_t from) {
  std::vector<uint8_t> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = uint8_t(from + i * 7);
  return v;
}

TEST(GatherLargeToRoot, PartsLargerThanARoundArriveWholeAndInRankOrder) {
  const std::vector<uint8_t> mine = counting(1000, 1), one = counting(0, 0),
                             two = counting(2501, 9);
  ScriptedRanks group({one, two}, 300 / 3);  // 300 bytes a round: 100 per rank
  const auto all = base::gatherLargeToRoot(group, mine, 300);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0], mine);
  EXPECT_EQ(all[1], one);
  EXPECT_EQ(all[2], two);
  EXPECT_EQ(group.rounds, 26);  // ceil(2501 / 100): the largest part sets the rounds
  EXPECT_EQ(group.largestPart, 100u);
}

}  // namespace
}  // namespace voxlink::scene
