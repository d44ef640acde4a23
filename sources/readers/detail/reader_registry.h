// SPDX-License-Identifier: BSD-3-Clause
// The table of volume readers that openVolume() consults in order.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sources/volume_source.h"

namespace voxlink::sources {

struct ReaderEntry {
  std::string name;                                 // --format value
  std::function<bool(const std::string&)> matches;  // claims a path by name or content
  std::function<Result<std::unique_ptr<VolumeSource>>(const std::string&, const OpenOptions&)> open;
  bool namedVariables = false;  // picks one of several named variables (OpenOptions::variable)
};

const std::vector<ReaderEntry>& readerRegistry();

// Lower-case file name ending, with ".gz" kept: "x.nii.gz" -> ".nii.gz".
std::string lowerExtension(const std::string& path);

}  // namespace voxlink::sources
