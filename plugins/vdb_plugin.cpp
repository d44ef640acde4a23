// libvoxlink_vdb.so: the OpenVDB grid reader and the OpenVDB footprint peer.
#include "convert/plugin_api.h"
#include "sources/readers/vdb_reader.h"
#include "convert/vdb_footprint.h"

extern "C" __attribute__((visibility("default"))) const voxlink::convert::VdbPluginApi* voxlink_vdb_plugin() {
  static const voxlink::convert::VdbPluginApi api{&voxlink::convert::openVdbDirect,
                                                  &voxlink::convert::measureVdbFootprintDirect};
  return &api;
}
