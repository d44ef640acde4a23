// SPDX-License-Identifier: BSD-3-Clause
#include "cli/output_options.h"

#include <cstdarg>
#include <cstdio>

#include "cli/progress_bar.h"

namespace voxlink::cli {

void OutputOptions::add(CLI::App* cmd, bool withProgress) {
  cmd->add_flag("-q,--quiet", quiet,
                "Print nothing but errors (no report, no progress bar); the exit status tells");
  if (withProgress)
    cmd->add_flag("--progress", progress,
                  "Draw the progress bar on stderr even when it is not a terminal");
}

bool OutputOptions::showProgress() const { return !quiet && (progress || stderrIsTerminal()); }

void OutputOptions::print(const char* format, ...) const {
  if (quiet) return;
  va_list args;
  va_start(args, format);
  std::vprintf(format, args);
  va_end(args);
}

void addThreadsOption(CLI::App* cmd, unsigned& threads) {
  cmd->add_option("--threads", threads, "Worker threads (0: every core; at most 1024)")
      ->capture_default_str();
}

}  // namespace voxlink::cli
