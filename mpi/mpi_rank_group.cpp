// SPDX-License-Identifier: BSD-3-Clause
#include "mpi/mpi_rank_group.h"

#include <mpi.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <thread>

namespace voxlink::mpi {
namespace {

constexpr int kAskTag = 7701;   // a worker asks rank 0 for the next item
constexpr int kItemTag = 7702;  // rank 0 answers with an item number, or `items` for "none left"

class MpiRankGroup final : public base::RankGroup {
 public:
  MpiRankGroup() {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~MpiRankGroup() override {
    if (dispatcher_.joinable()) dispatcher_.join();
    MPI_Finalize();
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  void allGather(const void* mine, size_t bytes, void* all) override {
    MPI_Allgather(mine, static_cast<int>(bytes), MPI_BYTE, all, static_cast<int>(bytes), MPI_BYTE,
                  MPI_COMM_WORLD);
  }

  std::vector<std::vector<uint8_t>> gatherToRoot(std::span<const uint8_t> mine) override {
    const int count = static_cast<int>(mine.size());
    std::vector<int> counts(static_cast<size_t>(size_));
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::vector<int> displs(static_cast<size_t>(size_), 0);
    int total = 0;
    for (size_t r = 0; r < counts.size(); ++r) displs[r] = total, total += counts[r];
    std::vector<uint8_t> all(rank_ == 0 ? static_cast<size_t>(total) : 0);
    MPI_Gatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, 0,
                MPI_COMM_WORLD);
    std::vector<std::vector<uint8_t>> parts;
    if (rank_ != 0) return parts;
    for (size_t r = 0; r < counts.size(); ++r)
      parts.emplace_back(all.begin() + displs[r], all.begin() + displs[r] + counts[r]);
    return parts;
  }

  void broadcast(std::string& text, int root) override {
    uint64_t length = text.size();
    MPI_Bcast(&length, 1, MPI_UINT64_T, root, MPI_COMM_WORLD);
    text.resize(length);
    MPI_Bcast(text.data(), static_cast<int>(length), MPI_CHAR, root, MPI_COMM_WORLD);
  }

  // Rank 0 converts too: its own items come from an atomic counter that a dispatcher thread
  // also serves to the other ranks (the only MPI caller while the queue runs, so
  // MPI_THREAD_SERIALIZED suffices). It polls with a sleep rather than blocking in MPI_Recv,
  // which would spin a core that rank 0 needs for its own conversions.
  void startQueue(uint64_t items) override {
    items_ = items;
    next_ = 0;
    MPI_Barrier(MPI_COMM_WORLD);
    if (rank_ != 0 || size_ == 1) return;
    dispatcher_ = std::thread([this] {
      int finished = 0;
      while (finished < size_ - 1) {
        int waiting = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, kAskTag, MPI_COMM_WORLD, &waiting, &status);
        if (!waiting) {
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
          continue;
        }
        char ask = 0;
        MPI_Recv(&ask, 1, MPI_CHAR, status.MPI_SOURCE, kAskTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        uint64_t item = next_.fetch_add(1);
        if (item >= items_) item = items_, ++finished;
        MPI_Send(&item, 1, MPI_UINT64_T, status.MPI_SOURCE, kItemTag, MPI_COMM_WORLD);
      }
    });
  }

  std::optional<uint64_t> nextItem() override {
    uint64_t item = items_;
    if (rank_ == 0) {
      item = next_.fetch_add(1);
    } else if (!drained_) {
      const char ask = 1;
      MPI_Send(&ask, 1, MPI_CHAR, 0, kAskTag, MPI_COMM_WORLD);
      MPI_Recv(&item, 1, MPI_UINT64_T, 0, kItemTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    }
    if (item < items_) return item;
    drained_ = true;
    return std::nullopt;
  }

  void finishQueue() override {
    if (dispatcher_.joinable()) dispatcher_.join();
    drained_ = false;
    MPI_Barrier(MPI_COMM_WORLD);
  }

 private:
  int rank_ = 0, size_ = 1;
  uint64_t items_ = 0;
  std::atomic<uint64_t> next_{0};
  bool drained_ = false;
  std::thread dispatcher_;
};

}  // namespace

bool launchedByMpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

std::unique_ptr<base::RankGroup> startMpi(int* argc, char*** argv) {
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided);
  return std::make_unique<MpiRankGroup>();
}

}  // namespace voxlink::mpi
