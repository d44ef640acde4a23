// The readers' side of their plugins: the public reader functions load the plugin that holds
// the heavy library and forward to it.
#include "convert/plugin_api.h"
#include "sources/readers/dicom_reader.h"
#include "sources/readers/vdb_reader.h"
#include "plugins/plugin_loader.h"

namespace voxlink::convert {

using plugins::pluginApi;

Result<std::unique_ptr<VolumeSource>> openDicomSeries(const std::string& dir,
                                                      const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(const DicomPluginApi* dicom,
                           pluginApi<DicomPluginApi>(kDicomPlugin, kDicomPluginEntry));
  return dicom->openSeries(dir, options);
}

Result<std::unique_ptr<VolumeSource>> openVdb(const std::string& path, const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(const VdbPluginApi* vdb, pluginApi<VdbPluginApi>(kVdbPlugin, kVdbPluginEntry));
  return vdb->open(path, options);
}

}  // namespace voxlink::convert
