// SPDX-License-Identifier: BSD-3-Clause
#include "base/rank_group.h"

#include <algorithm>
#include <cstring>

namespace voxlink {
inline namespace base {
namespace {

class SingleProcess final : public RankGroup {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  void allGather(const void* mine, size_t bytes, void* all) override {
    std::memmove(all, mine, bytes);
  }
  std::vector<std::vector<uint8_t>> gatherToRoot(std::span<const uint8_t> mine) override {
    return {std::vector<uint8_t>(mine.begin(), mine.end())};
  }
  void broadcast(std::string&, int) override {}
  void startQueue(uint64_t items) override {
    items_ = items;
    next_ = 0;
  }
  std::optional<uint64_t> nextItem() override {
    if (next_ >= items_) return std::nullopt;
    return next_++;
  }
  void finishQueue() override {}

 private:
  uint64_t items_ = 0, next_ = 0;
};

}  // namespace

RankGroup& singleProcess() {
  static SingleProcess group;
  return group;
}

std::vector<std::vector<uint8_t>> gatherLargeToRoot(RankGroup& group, std::span<const uint8_t> mine,
                                                    uint64_t roundBytes) {
  if (group.size() == 1) return group.gatherToRoot(mine);
  const uint64_t size = mine.size();
  std::vector<uint64_t> sizes(static_cast<size_t>(group.size()));
  group.allGather(&size, sizeof size, sizes.data());
  const uint64_t chunk = std::max<uint64_t>(1, roundBytes / sizes.size());
  uint64_t rounds = 0;
  for (uint64_t s : sizes) rounds = std::max(rounds, (s + chunk - 1) / chunk);
  std::vector<std::vector<uint8_t>> all(group.rank() == 0 ? sizes.size() : 0);
  for (size_t r = 0; r < all.size(); ++r) all[r].reserve(sizes[r]);
  for (uint64_t round = 0; round < rounds; ++round) {
    const uint64_t from = std::min(size, round * chunk);
    const auto parts = group.gatherToRoot(mine.subspan(from, std::min(chunk, size - from)));
    for (size_t r = 0; r < all.size(); ++r)
      all[r].insert(all[r].end(), parts[r].begin(), parts[r].end());
  }
  return all;
}

Status agree(RankGroup& group, const Status& mine) {
  if (group.size() == 1) return mine;
  struct Outcome {
    int32_t failed;
    int32_t code;
  };
  const Outcome own{mine ? 0 : 1, mine ? 0 : static_cast<int32_t>(mine.error().code)};
  std::vector<Outcome> all(static_cast<size_t>(group.size()));
  group.allGather(&own, sizeof own, all.data());
  int first = -1;
  for (int r = 0; r < group.size() && first < 0; ++r)
    if (all[static_cast<size_t>(r)].failed) first = r;
  if (first < 0) return Status::ok();
  std::string message = mine ? std::string() : mine.error().message;
  group.broadcast(message, first);
  return makeError(static_cast<ErrorCode>(all[static_cast<size_t>(first)].code), "rank ", first,
                   ": ", message);
}

}  // namespace base
}  // namespace voxlink
