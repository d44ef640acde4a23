// libvoxlink_dicom.so: the DICOM series reader with GDCM.
#include "plugins/plugin_api.h"
#include "sources/readers/dicom_reader.h"

const voxlink::plugins::DicomPluginApi* voxlink_dicom_plugin() {
  static const voxlink::plugins::DicomPluginApi api{&voxlink::convert::openDicomSeriesDirect};
  return &api;
}
