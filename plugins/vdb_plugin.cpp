// libvoxlink_vdb.so: the OpenVDB grid reader and the OpenVDB footprint peer.
#include "convert/vdb_footprint.h"
#include "plugins/plugin_api.h"
#include "sources/readers/vdb_reader.h"

const voxlink::plugins::VdbPluginApi* voxlink_vdb_plugin() {
  static const voxlink::plugins::VdbPluginApi api{&voxlink::convert::openVdbDirect,
                                                  &voxlink::convert::measureVdbFootprintDirect};
  return &api;
}
