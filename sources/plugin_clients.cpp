// The readers' side of their plugins: the public reader functions load the plugin that holds
// the heavy library and forward to it.
#include "plugins/plugin_api.h"
#include "plugins/plugin_loader.h"
#include "sources/readers/dicom_reader.h"
#include "sources/readers/vdb_reader.h"

namespace voxlink::convert {

using plugins::DicomPluginApi;
using plugins::pluginApi;
using plugins::VdbPluginApi;

Result<std::unique_ptr<VolumeSource>> openDicomSeries(const std::string& dir,
                                                      const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(
      const DicomPluginApi* dicom,
      pluginApi<DicomPluginApi>(plugins::kDicomPlugin, plugins::kDicomPluginEntry));
  return dicom->openSeries(dir, options);
}

Result<DicomFolderListing> listDicomFolder(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(
      const DicomPluginApi* dicom,
      pluginApi<DicomPluginApi>(plugins::kDicomPlugin, plugins::kDicomPluginEntry));
  return dicom->listSeries(path);
}

Result<std::unique_ptr<VolumeSource>> openVdb(const std::string& path, const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(const VdbPluginApi* vdb,
                           pluginApi<VdbPluginApi>(plugins::kVdbPlugin, plugins::kVdbPluginEntry));
  return vdb->open(path, options);
}

}  // namespace voxlink::convert
