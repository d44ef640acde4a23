// SPDX-License-Identifier: BSD-3-Clause
// The frames of a multi-frame DICOM file: RT Dose (GridFrameOffsetVector along the slice normal,
// DoseGridScaling) and Enhanced CT/MR (Shared and Per-frame Functional Groups: plane position,
// plane orientation, pixel measures, pixel value transformation).
#pragma once

#include <gdcmDataSet.h>

#include "sources/readers/detail/dicom_header.h"

namespace voxlink::sources {

// Fills h.frames from `first` (the image-level values) and the file's per-frame information;
// frames without a position of their own leave h.hasPosition false. kCorrupt when the per-frame
// information disagrees with NumberOfFrames or is missing where the SOP class requires it;
// kUnsupported when frames differ in orientation or pixel spacing. Messages name the tag.
Status readFrames(const gdcm::DataSet& ds, const DicomSlice& first, DicomFileHeader& h);

}  // namespace voxlink::sources
