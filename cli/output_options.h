// SPDX-License-Identifier: BSD-3-Clause
// The options every subcommand spells and means the same way (docs/cli.md): -q/--quiet,
// --progress and --threads.
#pragma once

#include <CLI/CLI.hpp>

namespace voxlink::cli {

struct OutputOptions {
  bool quiet = false;
  bool progress = false;

  // -q/--quiet on `cmd`; with `withProgress` also --progress (commands that report progress).
  void add(CLI::App* cmd, bool withProgress);
  // The progress bar is drawn with --progress, else when stderr is a terminal; never with -q.
  bool showProgress() const;
  // printf on stdout, unless -q: the report a command prints on success.
  void print(const char* format, ...) const __attribute__((format(printf, 2, 3)));
};

// --threads N: worker threads, 0 for every core (the libraries refuse more than 1024).
void addThreadsOption(CLI::App* cmd, unsigned& threads);

}  // namespace voxlink::cli
