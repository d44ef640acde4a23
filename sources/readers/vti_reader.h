// SPDX-License-Identifier: BSD-3-Clause
// VTK XML image data (.vti): one piece, one scalar point-data array, inline base64 or appended
// (raw or base64) data, optionally zlib-compressed in blocks. The array is decoded whole at open
// (VTK XML keeps it inside the XML) and then served from memory.
#pragma once

#include <memory>
#include <string>

#include "sources/volume_source.h"

namespace voxlink::sources {

Result<std::unique_ptr<VolumeSource>> openVti(const std::string& path, const OpenOptions& options);

}  // namespace voxlink::sources
