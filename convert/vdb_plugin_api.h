// SPDX-License-Identifier: BSD-3-Clause
// The OpenVDB plugin's table for convert/: the footprint peer (convert/vdb_footprint.h) and the
// OpenVDB export (convert/vdb_export.h). The module, libvoxlink_vdb.so (sources::kVdbPlugin),
// serves the reader's table (sources/plugin_api.h) from its other entry; each table lives beside
// its client so that no include runs from sources/ up to convert/.
#pragma once

#include <string>

#include "base/error.h"
#include "base/progress.h"
#include "convert/vdb_export.h"
#include "format/voxlink_file.h"
#include "report/footprint.h"

namespace voxlink::convert {

struct VdbExportPluginApi {
  Result<report::PeerFootprint> (*measureFootprint)(const format::VoxLinkFile& file);
  Result<VdbExportSummary> (*exportVdb)(const format::VoxLinkFile& file, const std::string& path,
                                        const base::ProgressCallback& progress);
};
inline constexpr const char* kVdbExportPluginEntry = "voxlink_vdb_export_plugin";

}  // namespace voxlink::convert

// The entry, defined in plugins/vdb_plugin.cpp.
extern "C" __attribute__((visibility("default"))) const voxlink::convert::VdbExportPluginApi*
voxlink_vdb_export_plugin();
