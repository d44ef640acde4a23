// SPDX-License-Identifier: BSD-3-Clause
// DICOM volumes (GDCM 3) from a folder (searched recursively; one series picked with
// OpenOptions::dicomSeries) or one file: single-frame files and the frames of multi-frame files
// (RT Dose, Enhanced CT/MR) ordered by position along the slice normal, RescaleSlope/
// RescaleIntercept or DoseGridScaling applied.
#pragma once

#include <memory>
#include <string>

#include "sources/readers/dicom_series.h"
#include "sources/volume_source.h"

namespace voxlink::sources {

// Through the DICOM plugin (libvoxlink_dicom.so, GDCM), loaded on first use.
Result<std::unique_ptr<VolumeSource>> openDicomSeries(const std::string& dir,
                                                      const OpenOptions& options);
// The series under a folder, through the plugin (`voxlink dicom list`).
Result<DicomFolderListing> listDicomFolder(const std::string& path);
// The implementation inside the plugin.
Result<std::unique_ptr<VolumeSource>> openDicomSeriesDirect(const std::string& dir,
                                                            const OpenOptions& options);

}  // namespace voxlink::sources
