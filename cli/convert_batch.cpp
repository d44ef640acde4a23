// SPDX-License-Identifier: BSD-3-Clause
#include "cli/convert_batch.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <new>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "cli/printable_message.h"
#include "cli/process_ranks.h"
#include "convert/batch.h"
#include "format/validator.h"
#include "pack/open_file.h"

namespace voxlink::cli {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Per rank, summed at the end.
struct Tally {
  uint64_t converted = 0, skipped = 0, failed = 0, voxels = 0, bytes = 0;
  double busySeconds = 0;
};

// One line, written at once, so lines of different ranks do not interleave.
void printLine(const nlohmann::ordered_json& j) {
  const std::string line = j.dump() + "\n";
  std::fwrite(line.data(), 1, line.size(), stdout);
  std::fflush(stdout);
}

Status prepareOutDir(const std::string& outDir) {
  std::error_code ec;
  std::filesystem::create_directories(outDir, ec);
  if (ec || !std::filesystem::is_directory(outDir))
    return makeError(ErrorCode::kIo, outDir,
                     ": cannot create the output folder: ", ec ? ec.message() : "not a folder");
  return Status::ok();
}

}  // namespace

int runBatch(const std::string& listPath, const std::string& outDir, bool resume,
             const ConvertOneFile& convertOne) {
  base::RankGroup& ranks = processRanks();
  const auto start = Clock::now();
  auto items = convert::readBatchList(listPath, outDir);
  Status ready = items.status();
  if (ready && ranks.rank() == 0) ready = prepareOutDir(outDir);
  if (Status all = base::agree(ranks, ready); !all) return reportOnRankZero(all);

  Tally tally;
  ranks.startQueue(items->size());
  while (std::optional<uint64_t> next = ranks.nextItem()) {
    const convert::BatchItem& item = (*items)[*next];
    nlohmann::ordered_json j;
    j["input"] = item.input;
    j["output"] = item.output;
    const auto fileStart = Clock::now();
    if (resume && std::filesystem::exists(item.output) && pack::openValidatedFile(item.output)) {
      j["status"] = "skipped";
      j["reason"] = "the output exists and validates";
      ++tally.skipped;
    } else {
      Result<convert::ConvertSummary> done = makeError(ErrorCode::kIo, "not run");
      try {
        done = convertOne(item.input, item.output);
      } catch (const std::bad_alloc&) {
        done = makeError(ErrorCode::kTooLarge, item.input, ": out of memory");
      }
      if (done) {
        j["status"] = "converted";
        j["voxels"] = done->voxels;
        j["bytes"] = done->bytes;
        j["bytes_per_voxel"] = done->voxels ? double(done->bytes) / done->voxels : 0.0;
        ++tally.converted;
        tally.voxels += done->voxels;
        tally.bytes += done->bytes;
      } else {
        j["status"] = "failed";
        j["error"] = printableMessage(done.message());
        ++tally.failed;
      }
    }
    const double seconds = secondsSince(fileStart);
    tally.busySeconds += seconds;
    j["seconds"] = seconds;
    j["rank"] = ranks.rank();
    printLine(j);
  }
  ranks.finishQueue();

  std::vector<Tally> all(static_cast<size_t>(ranks.size()));
  ranks.allGather(&tally, sizeof tally, all.data());
  Tally sum;
  double busiest = 0;
  for (const Tally& t : all) {
    sum.converted += t.converted;
    sum.skipped += t.skipped;
    sum.failed += t.failed;
    sum.voxels += t.voxels;
    sum.bytes += t.bytes;
    sum.busySeconds += t.busySeconds;
    busiest = std::max(busiest, t.busySeconds);
  }
  if (ranks.rank() == 0) {
    nlohmann::ordered_json j;
    j["summary"] = {{"files", items->size()},
                    {"converted", sum.converted},
                    {"skipped", sum.skipped},
                    {"failed", sum.failed},
                    {"voxels", sum.voxels},
                    {"bytes", sum.bytes},
                    {"ranks", ranks.size()},
                    {"seconds", secondsSince(start)},
                    {"busy_seconds", sum.busySeconds},
                    {"busiest_rank_seconds", busiest}};
    printLine(j);
  }
  return sum.failed ? 1 : 0;
}

}  // namespace voxlink::cli
