// The executables' side of the OpenVDB export: validates, loads libvoxlink_vdb.so, forwards.
#include "convert/vdb_export.h"
#include "format/validator.h"
#include "plugins/plugin_api.h"
#include "plugins/plugin_loader.h"

namespace voxlink::convert {

Result<VdbExportSummary> exportVdb(const format::VoxLinkFile& file, const std::string& path,
                                   const format::ProgressCallback& progress) {
  // Validating a fifth of the bar, building and writing the grids the rest.
  VOXLINK_RETURN_IF_ERROR(
      format::validateFile(file, format::progressPart(progress, 0, 0.2)).status());
  VOXLINK_ASSIGN_OR_RETURN(
      const plugins::VdbPluginApi* vdb,
      plugins::pluginApi<plugins::VdbPluginApi>(plugins::kVdbPlugin, plugins::kVdbPluginEntry));
  return vdb->exportVdb(file, path, format::progressPart(progress, 0.2, 1));
}

}  // namespace voxlink::convert
