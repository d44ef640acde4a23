// SPDX-License-Identifier: BSD-3-Clause
// MetaImage volumes (.mhd + data file(s), .mha with LOCAL data), raw or zlib-compressed.
#pragma once

#include <memory>
#include <string>

#include "sources/volume_source.h"

namespace voxlink::sources {

Result<std::unique_ptr<VolumeSource>> openMetaImage(const std::string& path,
                                                    const OpenOptions& options);

}  // namespace voxlink::sources
