// SPDX-License-Identifier: BSD-3-Clause
// Command-line options that say how to open a dense source volume (shared by every command
// that reads one).
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "sources/volume_source.h"

namespace voxlink::cli {

struct SourceArgs {
  std::vector<uint32_t> dims;
  std::string type;
  std::string endian = "little";
  uint64_t headerBytes = 0;
  std::vector<double> spacing;
  std::string format;
  std::string vdbGrid;
  std::string variable;
  std::string dicomSeries;
};

void addSourceOptions(CLI::App& cmd, SourceArgs& args);
Result<sources::OpenOptions> toOpenOptions(const SourceArgs& args);

}  // namespace voxlink::cli
