// SPDX-License-Identifier: BSD-3-Clause
// The readers' side of their plugins: the public reader functions load the plugin that holds
// the heavy library and forward to it.
#include "base/plugin_loader.h"
#include "sources/plugin_api.h"
#include "sources/readers/dicom_reader.h"
#include "sources/readers/vdb_reader.h"

namespace voxlink::sources {

using base::pluginApi;
using sources::DicomPluginApi;
using sources::VdbPluginApi;

Result<std::unique_ptr<VolumeSource>> openDicomSeries(const std::string& dir,
                                                      const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(
      const DicomPluginApi* dicom,
      pluginApi<DicomPluginApi>(sources::kDicomPlugin, sources::kDicomPluginEntry));
  return dicom->openSeries(dir, options);
}

Result<DicomFolderListing> listDicomFolder(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(
      const DicomPluginApi* dicom,
      pluginApi<DicomPluginApi>(sources::kDicomPlugin, sources::kDicomPluginEntry));
  return dicom->listSeries(path);
}

Result<std::unique_ptr<VolumeSource>> openVdb(const std::string& path, const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(const VdbPluginApi* vdb,
                           pluginApi<VdbPluginApi>(sources::kVdbPlugin, sources::kVdbPluginEntry));
  return vdb->open(path, options);
}

}  // namespace voxlink::sources
