// SPDX-License-Identifier: BSD-3-Clause
// libvoxlink_vdb.so: the OpenVDB grid reader, the OpenVDB footprint peer and the export.
#include "convert/vdb_export.h"
#include "convert/vdb_footprint.h"
#include "convert/vdb_plugin_api.h"
#include "sources/plugin_api.h"
#include "sources/readers/vdb_reader.h"

const voxlink::sources::VdbPluginApi* voxlink_vdb_plugin() {
  static const voxlink::sources::VdbPluginApi api{&voxlink::sources::openVdbDirect};
  return &api;
}

const voxlink::convert::VdbExportPluginApi* voxlink_vdb_export_plugin() {
  static const voxlink::convert::VdbExportPluginApi api{
      &voxlink::convert::measureVdbFootprintDirect, &voxlink::convert::exportVdbDirect};
  return &api;
}
