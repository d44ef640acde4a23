// SPDX-License-Identifier: BSD-3-Clause
// The executables' side of the OpenVDB export: validates, loads libvoxlink_vdb.so, forwards.
#include "base/plugin_loader.h"
#include "convert/vdb_export.h"
#include "convert/vdb_plugin_api.h"
#include "format/validator.h"
#include "sources/plugin_api.h"

namespace voxlink::convert {

Result<VdbExportSummary> exportVdb(const format::VoxLinkFile& file, const std::string& path,
                                   const base::ProgressCallback& progress) {
  // Validating a fifth of the bar, building and writing the grids the rest.
  VOXLINK_RETURN_IF_ERROR(
      format::validateFile(file, base::progressPart(progress, 0, 0.2)).status());
  VOXLINK_ASSIGN_OR_RETURN(
      const VdbExportPluginApi* vdb,
      base::pluginApi<VdbExportPluginApi>(sources::kVdbPlugin, kVdbExportPluginEntry));
  return vdb->exportVdb(file, path, base::progressPart(progress, 0.2, 1));
}

}  // namespace voxlink::convert
