// SPDX-License-Identifier: BSD-3-Clause
// Each `voxlink` subcommand lives in its own cmd_*.cpp and registers itself here. A command
// turns library errors into one line on stderr and a non-zero exit status.
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <string>

#include "base/error.h"

namespace voxlink::cli {

// Adds a subcommand to `app`; the returned callback runs it and gives the exit status.
using CommandRunner = std::function<int()>;
using CommandFactory = CommandRunner (*)(CLI::App& app);

// Prints "voxlink: <message>" on stderr and returns the exit status for the error's kind.
int reportError(const Error& error);
int reportError(const Status& status);
// The exit status reportError gives, without printing.
int exitStatusFor(const Error& error);
// With several MPI ranks that agreed on `status` (base::agree): only rank 0 prints it; every
// rank returns the same exit status.
int reportOnRankZero(const Status& status);

// Option check for numbers that must be finite: CLI11 itself reads "nan" and "inf" as doubles.
// Each comma-separated element is checked, so it also guards list options like --keep-outside.
inline CLI::Validator finiteNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::string rest = text;
        for (size_t at = 0; at <= rest.size();) {
          const size_t comma = std::min(rest.find(',', at), rest.size());
          const std::string word = rest.substr(at, comma - at);
          char* end = nullptr;
          const double v = std::strtod(word.c_str(), &end);
          if (!word.empty() && end == word.c_str() + word.size() && !std::isfinite(v))
            return word + " is not a finite number";
          at = comma + 1;
        }
        return "";
      },
      "FINITE");
}

// Subcommands, in the order --help lists them.
CommandRunner addConvertCommand(CLI::App& app);
CommandRunner addInfoCommand(CLI::App& app);
CommandRunner addExportCommand(CLI::App& app);
CommandRunner addPackCommand(CLI::App& app);
CommandRunner addUnpackCommand(CLI::App& app);
CommandRunner addValidateCommand(CLI::App& app);
CommandRunner addSceneCommand(CLI::App& app);
CommandRunner addStatsCommand(CLI::App& app);
CommandRunner addDicomCommand(CLI::App& app);
CommandRunner addKrigeCommand(CLI::App& app);
CommandRunner addGrfCommand(CLI::App& app);
CommandRunner addRenderCommand(CLI::App& app);
CommandRunner addBenchRenderCommand(CLI::App& app);
CommandRunner addViewCommand(CLI::App& app);
CommandRunner addRenderExactCommand(CLI::App& app);

}  // namespace voxlink::cli
