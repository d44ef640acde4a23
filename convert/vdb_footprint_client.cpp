// The footprint comparison's side of the OpenVDB plugin: loads libvoxlink_vdb.so and forwards.
#include "convert/vdb_footprint.h"
#include "format/validator.h"
#include "plugins/plugin_api.h"
#include "plugins/plugin_loader.h"

namespace voxlink::convert {

Result<format::PeerFootprint> measureVdbFootprint(const format::VoxLinkFile& file) {
  // The comparison walks every voxel through BVOX, ROWS and MASK, which open() does not check
  // (that costs a pass over the data): a damaged file must give an error, not a crash.
  if (auto valid = format::validateFile(file); !valid)
    return makeError(valid.code(), valid.message(), "; the OpenVDB comparison needs a valid file");
  VOXLINK_ASSIGN_OR_RETURN(
      const plugins::VdbPluginApi* vdb,
      plugins::pluginApi<plugins::VdbPluginApi>(plugins::kVdbPlugin, plugins::kVdbPluginEntry));
  return vdb->measureFootprint(file);
}

}  // namespace voxlink::convert
