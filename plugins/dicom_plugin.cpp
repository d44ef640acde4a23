// SPDX-License-Identifier: BSD-3-Clause
// libvoxlink_dicom.so: the DICOM series reader with GDCM.
#include "sources/plugin_api.h"
#include "sources/readers/dicom_reader.h"
#include "sources/readers/dicom_series.h"

const voxlink::sources::DicomPluginApi* voxlink_dicom_plugin() {
  static const voxlink::sources::DicomPluginApi api{&voxlink::sources::openDicomSeriesDirect,
                                                    &voxlink::sources::listDicomSeries};
  return &api;
}
