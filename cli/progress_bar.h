// A one-line progress bar on stderr, drawn only when stderr is a terminal (or when forced).
#pragma once

#include <chrono>
#include <string>

namespace voxlink::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  ~ProgressBar();
  void update(double fraction, const char* stage);
  void finish();

 private:
  bool enabled_;
  int lastPermille_ = -1;
  std::string lastStage_;
  std::chrono::steady_clock::time_point start_;
};

bool stderrIsTerminal();

}  // namespace voxlink::cli
