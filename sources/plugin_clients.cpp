// The converter's side of its plugins: the public reader functions load the plugin that holds
// the heavy library and forward to it.
#include "convert/plugin_api.h"
#include "convert/readers/dicom_reader.h"
#include "convert/readers/vdb_reader.h"
#include "convert/vdb_footprint.h"
#include "format/validator.h"
#include "plugins/plugin_loader.h"

namespace voxlink::convert {
namespace {

template <class Api>
Result<const Api*> api(const char* file, const char* entry) {
  VOXLINK_ASSIGN_OR_RETURN(void* e, plugins::pluginEntry(file, entry));
  return reinterpret_cast<const Api* (*)()>(e)();
}

}  // namespace

Result<std::unique_ptr<VolumeSource>> openDicomSeries(const std::string& dir,
                                                      const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(const DicomPluginApi* dicom,
                           api<DicomPluginApi>(kDicomPlugin, kDicomPluginEntry));
  return dicom->openSeries(dir, options);
}

Result<std::unique_ptr<VolumeSource>> openVdb(const std::string& path, const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(const VdbPluginApi* vdb, api<VdbPluginApi>(kVdbPlugin, kVdbPluginEntry));
  return vdb->open(path, options);
}

Result<format::PeerFootprint> measureVdbFootprint(const format::VoxLinkFile& file) {
  // The comparison walks every voxel through BVOX, ROWS and MASK, which open() does not check
  // (that costs a pass over the data): a damaged file must give an error, not a crash.
  if (auto valid = format::validateFile(file); !valid)
    return makeError(valid.code(), valid.message(), "; the OpenVDB comparison needs a valid file");
  VOXLINK_ASSIGN_OR_RETURN(const VdbPluginApi* vdb, api<VdbPluginApi>(kVdbPlugin, kVdbPluginEntry));
  return vdb->measureFootprint(file);
}

}  // namespace voxlink::convert
