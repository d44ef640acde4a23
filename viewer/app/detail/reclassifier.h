// SPDX-License-Identifier: BSD-3-Clause
// Re-classification in a background thread (paper, section 3.1.3): when a transfer function
// gives opacity to values the file's pre-classification removed, the viewer re-converts the
// source recorded in META, keeping what the new transfer function shows, and reloads.
#pragma once

#include <atomic>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "format/voxlink_file.h"
#include "tf/transfer_function.h"

namespace voxlink::viewer {

class Reclassifier {
 public:
  Reclassifier() = default;
  Reclassifier(const Reclassifier&) = delete;
  Reclassifier& operator=(const Reclassifier&) = delete;
  ~Reclassifier();  // cancels and joins a running job

  // Where the new file goes: beside `path`, as NAME.reclassified.vxl.
  static std::string outputPathFor(const std::string& path);

  // Starts converting the file's recorded source, keeping the values `tf` shows. Fails at once
  // when the source is not recorded or cannot be found; later failures come from result().
  Status start(const format::VoxLinkFile& file, const tf::TransferFunction& tf,
               const std::string& outputPath);
  bool running() const { return running_.load(); }
  double progress() const { return progress_.load(); }
  std::string stage() const;
  void cancel() { cancel_.store(true); }
  // Once a job has ended: the written file's path, or the error. Empty while running or idle.
  std::optional<Result<std::string>> takeResult();

 private:
  void join();

  std::thread thread_;
  std::atomic<bool> running_{false}, cancel_{false};
  std::atomic<double> progress_{0.0};
  mutable std::mutex mutex_;
  std::string stage_;
  std::optional<Result<std::string>> result_;
};

}  // namespace voxlink::viewer
