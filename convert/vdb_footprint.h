// SPDX-License-Identifier: BSD-3-Clause
// The OpenVDB peer of the footprint report: the same voxels and values held as an
// openvdb::FloatGrid in memory, measured with OpenVDB's own memUsage().
#pragma once

#include "base/error.h"
#include "format/voxlink_file.h"
#include "report/footprint.h"

namespace voxlink::convert {

// Through the OpenVDB plugin (libvoxlink_vdb.so), loaded on first use.
Result<report::PeerFootprint> measureVdbFootprint(const format::VoxLinkFile& file);
// The implementation inside the plugin.
Result<report::PeerFootprint> measureVdbFootprintDirect(const format::VoxLinkFile& file);

}  // namespace voxlink::convert
