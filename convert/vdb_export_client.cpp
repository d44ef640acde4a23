// The executables' side of the OpenVDB export: validates, loads libvoxlink_vdb.so, forwards.
#include "convert/vdb_export.h"
#include "format/validator.h"
#include "plugins/plugin_api.h"
#include "plugins/plugin_loader.h"

namespace voxlink::convert {

Result<VdbExportSummary> exportVdb(const format::VoxLinkFile& file, const std::string& path) {
  VOXLINK_RETURN_IF_ERROR(format::validateFile(file).status());
  VOXLINK_ASSIGN_OR_RETURN(
      const plugins::VdbPluginApi* vdb,
      plugins::pluginApi<plugins::VdbPluginApi>(plugins::kVdbPlugin, plugins::kVdbPluginEntry));
  return vdb->exportVdb(file, path);
}

}  // namespace voxlink::convert
