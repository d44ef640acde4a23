// SPDX-License-Identifier: BSD-3-Clause
// Image stacks through OpenImageIO: a folder of 2-D slices (TIFF, PNG, ...) ordered by the
// numbers in their names ("slice2" before "slice10"), or one multi-page TIFF.
#pragma once

#include <memory>
#include <string>

#include "sources/volume_source.h"

namespace voxlink::sources {

// File name endings treated as 2-D slice images.
bool isSliceImageName(const std::string& path);

Result<std::unique_ptr<VolumeSource>> openImageStack(const std::string& path,
                                                     const OpenOptions& options);

}  // namespace voxlink::sources
