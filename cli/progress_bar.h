// SPDX-License-Identifier: BSD-3-Clause
// A one-line progress bar on stderr, drawn only when stderr is a terminal (or when forced).
#pragma once

#include <chrono>
#include <string>

#include "base/error.h"
#include "base/progress.h"

namespace voxlink::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  ~ProgressBar();
  void update(double fraction, const char* stage);
  void finish();
  // Moves this bar from a library call's progress reports; the bar must outlive the callback.
  base::ProgressCallback callback();
  // Clears the bar, then reports `error` on a line of its own (reportError); the exit status.
  int fail(const Error& error);

 private:
  bool enabled_;
  int lastPermille_ = -1;
  std::string lastStage_;
  std::chrono::steady_clock::time_point start_;
};

bool stderrIsTerminal();

}  // namespace voxlink::cli
