// SPDX-License-Identifier: BSD-3-Clause
// The footprint comparison's side of the OpenVDB plugin: loads libvoxlink_vdb.so and forwards.
#include "base/plugin_loader.h"
#include "convert/vdb_footprint.h"
#include "convert/vdb_plugin_api.h"
#include "format/validator.h"
#include "sources/plugin_api.h"

namespace voxlink::convert {

Result<report::PeerFootprint> measureVdbFootprint(const format::VoxLinkFile& file) {
  // The comparison walks every voxel through BVOX, ROWS and MASK, which open() does not check
  // (that costs a pass over the data): a damaged file must give an error, not a crash.
  if (auto valid = format::validateFile(file); !valid)
    return makeError(valid.code(), valid.message(), "; the OpenVDB comparison needs a valid file");
  VOXLINK_ASSIGN_OR_RETURN(
      const VdbExportPluginApi* vdb,
      base::pluginApi<VdbExportPluginApi>(sources::kVdbPlugin, kVdbExportPluginEntry));
  return vdb->measureFootprint(file);
}

}  // namespace voxlink::convert
