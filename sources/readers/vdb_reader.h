// SPDX-License-Identifier: BSD-3-Clause
// OpenVDB .vdb float grids served as a dense volume over the active voxel bounding box, slab by
// slab, so memory stays bounded by the grid itself plus the slabs asked for.
#pragma once

#include <memory>
#include <string>

#include "sources/volume_source.h"

namespace voxlink::sources {

// The grid is options.vdbGrid, or the first float grid in the file.
// Through the OpenVDB plugin (libvoxlink_vdb.so), loaded on first use.
Result<std::unique_ptr<VolumeSource>> openVdb(const std::string& path, const OpenOptions& options);
// The implementation inside the plugin.
Result<std::unique_ptr<VolumeSource>> openVdbDirect(const std::string& path,
                                                    const OpenOptions& options);

}  // namespace voxlink::sources
