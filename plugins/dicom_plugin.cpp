// libvoxlink_dicom.so: the DICOM series reader with GDCM.
#include "convert/plugin_api.h"
#include "sources/readers/dicom_reader.h"

extern "C" __attribute__((visibility("default"))) const voxlink::convert::DicomPluginApi* voxlink_dicom_plugin() {
  static const voxlink::convert::DicomPluginApi api{&voxlink::convert::openDicomSeriesDirect};
  return &api;
}
