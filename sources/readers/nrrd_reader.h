// SPDX-License-Identifier: BSD-3-Clause
// NRRD volumes (.nrrd attached, .nhdr detached): raw or gzip data in one file, one file per
// slice ("data file: quarter.%d 1 93 1") or a LIST of files.
#pragma once

#include <memory>
#include <string>

#include "sources/volume_source.h"

namespace voxlink::sources {

Result<std::unique_ptr<VolumeSource>> openNrrd(const std::string& path, const OpenOptions& options);

}  // namespace voxlink::sources
