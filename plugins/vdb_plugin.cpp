// libvoxlink_vdb.so: the OpenVDB grid reader, the OpenVDB footprint peer and the export.
#include "convert/vdb_export.h"
#include "convert/vdb_footprint.h"
#include "plugins/plugin_api.h"
#include "sources/readers/vdb_reader.h"

const voxlink::plugins::VdbPluginApi* voxlink_vdb_plugin() {
  static const voxlink::plugins::VdbPluginApi api{&voxlink::convert::openVdbDirect,
                                                  &voxlink::convert::measureVdbFootprintDirect,
                                                  &voxlink::convert::exportVdbDirect};
  return &api;
}
