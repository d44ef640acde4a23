#include "convert/rank_group.h"

#include <cstring>

namespace voxlink::convert {
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

}  // namespace voxlink::convert
