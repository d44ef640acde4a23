// SPDX-License-Identifier: BSD-3-Clause
// Voreen .vvd volumes: an XML header naming one little-endian raw file (RawData filename,
// format, x, y, z) with Spacing and Offset meta items.
#pragma once

#include <memory>
#include <string>

#include "sources/volume_source.h"

namespace voxlink::sources {

Result<std::unique_ptr<VolumeSource>> openVvd(const std::string& path, const OpenOptions& options);

}  // namespace voxlink::sources
