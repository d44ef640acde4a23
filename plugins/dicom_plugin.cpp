// libvoxlink_dicom.so: the DICOM series reader with GDCM.
#include "plugins/plugin_api.h"
#include "sources/readers/dicom_reader.h"
#include "sources/readers/dicom_series.h"

const voxlink::plugins::DicomPluginApi* voxlink_dicom_plugin() {
  static const voxlink::plugins::DicomPluginApi api{&voxlink::convert::openDicomSeriesDirect,
                                                    &voxlink::convert::listDicomSeries};
  return &api;
}
