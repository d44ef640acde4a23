// The OpenVDB peer of the footprint report: the same voxels and values held as an
// openvdb::FloatGrid in memory, measured with OpenVDB's own memUsage().
#pragma once

#include "format/error.h"
#include "format/footprint.h"
#include "format/voxlink_file.h"

namespace voxlink::convert {

// Through the OpenVDB plugin (libvoxlink_vdb.so), loaded on first use.
Result<format::PeerFootprint> measureVdbFootprint(const format::VoxLinkFile& file);
// The implementation inside the plugin.
Result<format::PeerFootprint> measureVdbFootprintDirect(const format::VoxLinkFile& file);

}  // namespace voxlink::convert
