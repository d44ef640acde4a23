// SPDX-License-Identifier: BSD-3-Clause
#include "cli/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "cli/command.h"

namespace voxlink::cli {

bool stderrIsTerminal() { return isatty(STDERR_FILENO) == 1; }

ProgressBar::ProgressBar(bool enabled)
    : enabled_(enabled), start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(double fraction, const char* stage) {
  if (!enabled_) return;
  const int permille = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 1000);
  if (permille == lastPermille_ && lastStage_ == stage) return;
  lastPermille_ = permille;
  lastStage_ = stage;
  const int width = 30;
  const int filled = permille * width / 1000;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr, "\r[%.*s%*s] %5.1f%% %-12s %6.1f s", filled,
               "##############################", width - filled, "", permille / 10.0, stage,
               elapsed);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (!enabled_ || lastPermille_ < 0) return;
  std::fprintf(stderr, "\r%*s\r", 70, "");
  std::fflush(stderr);
  lastPermille_ = -1;
}

base::ProgressCallback ProgressBar::callback() {
  return [this](double fraction, const char* stage) { update(fraction, stage); };
}

int ProgressBar::fail(const Error& error) {
  finish();
  return reportError(error);
}

}  // namespace voxlink::cli
