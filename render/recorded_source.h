// SPDX-License-Identifier: BSD-3-Clause
// The dense source a VoxLink file was converted from, as its META section records it
// ({"source": {"path", "format", "type", "dims", "open_options"}}): what the reference renderer,
// the dense peer renderer and re-classification read.
#pragma once

#include <string>

#include "format/voxlink_file.h"
#include "render/dense_volume.h"
#include "sources/volume_source.h"

namespace voxlink::render {

struct RecordedSource {
  std::string path;  // resolved: as recorded, or relative to the .vxl file's directory
  sources::OpenOptions options;
};

// Fails when META names no source or the file it names cannot be found.
Result<RecordedSource> recordedSource(const format::VoxLinkFile& file);

// `overridePath` with `options` when given, else the recorded source.
Result<RecordedSource> chosenSource(const format::VoxLinkFile& file,
                                    const std::string& overridePath,
                                    const sources::OpenOptions& options);

// Opens `overridePath` (with `options`) when given, else the recorded source, and checks that its
// dims match the file's.
Result<DenseVolume> loadSourceVolume(const format::VoxLinkFile& file,
                                     const std::string& overridePath,
                                     const sources::OpenOptions& options);

}  // namespace voxlink::render
