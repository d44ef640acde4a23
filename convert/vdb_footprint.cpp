// SPDX-License-Identifier: BSD-3-Clause
#include "convert/vdb_footprint.h"

#include <openvdb/openvdb.h>

#include <chrono>

#include "format/voxel_locator.h"

namespace voxlink::convert {

Result<report::PeerFootprint> measureVdbFootprintDirect(const format::VoxLinkFile& file) {
  openvdb::initialize();
  const auto start = std::chrono::steady_clock::now();
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  {
    auto accessor = grid->getAccessor();
    format::VoxelLocator locator(file);
    locator.forEachVoxel([&](uint32_t x, uint32_t y, uint32_t z, uint64_t index) {
      accessor.setValueOn(openvdb::Coord(int(x), int(y), int(z)),
                          static_cast<float>(file.value(index)));
    });
  }
  grid->pruneGrid();  // as tools::copyFromDense does
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report::PeerFootprint peer;
  peer.name = "OpenVDB FloatGrid";
  peer.bytes = grid->memUsage();
  peer.bytesPerVoxel = file.voxelCount() ? double(peer.bytes) / file.voxelCount() : 0.0;
  peer.seconds = seconds;
  peer.note = "OpenVDB " OPENVDB_LIBRARY_VERSION_STRING
              ", values only (no gradients), pruned, in memory, active voxels = " +
              std::to_string(grid->activeVoxelCount());
  return peer;
}

}  // namespace voxlink::convert
