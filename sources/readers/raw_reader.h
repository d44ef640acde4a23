// SPDX-License-Identifier: BSD-3-Clause
// Headerless raw volumes: dims, type and byte order come from the caller. Also the data part
// of formats with a detached header (NRRD, MetaImage, Voreen .vvd) whose data is one raw file.
#pragma once

#include <memory>
#include <string>

#include "sources/volume_source.h"

namespace voxlink::sources {

// Maps `dataPath` and serves slices from bytes [headerBytes, headerBytes + volume size).
// `info.path` names the volume in messages; the file must hold at least that many bytes.
// When `exactSize` is set (plain raw input), a file of any other size is an error, since that
// almost always means wrong dims or type.
Result<std::unique_ptr<VolumeSource>> openRawData(const std::string& dataPath, VolumeInfo info,
                                                  Endian endian, uint64_t headerBytes,
                                                  bool exactSize);

// A raw file named on the command line (needs options.dims and options.type).
Result<std::unique_ptr<VolumeSource>> openRaw(const std::string& path, const OpenOptions& options);

}  // namespace voxlink::sources
