// SPDX-License-Identifier: BSD-3-Clause
// Shared by the dense-reader targets: write the input's files, open the main one with a reader,
// read what it serves.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "fuzz/fuzz_input.h"
#include "fuzz/fuzz_targets.h"
#include "sources/volume_source.h"

namespace voxlink::fuzz {

using OpenFn = std::function<Result<std::unique_ptr<sources::VolumeSource>>(
    const std::string& path, const sources::OpenOptions& options)>;

// Writes the input's files (main file `mainName`) to the scratch dir, opens the main file (or
// the dir itself when `openDir`) with `open` and drains the volume.
Status openAndDrain(Input input, const std::string& mainName, const OpenFn& open,
                    const sources::OpenOptions& options = {}, bool openDir = false);

// True when the input starts with gzip's (or zip's) magic bytes: the main file then gets the
// name ending that makes a reader decompress it.
bool startsWithGzip(Input input);
bool startsWithZip(Input input);

}  // namespace voxlink::fuzz
