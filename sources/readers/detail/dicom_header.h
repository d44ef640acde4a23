// SPDX-License-Identifier: BSD-3-Clause
// The header of one DICOM file as the series scan needs it: identity (series, modality), pixel
// format, and one DicomSlice per frame with its position and rescale. Multi-frame files get
// their frames from GridFrameOffsetVector (RT Dose) or the functional groups (Enhanced CT/MR).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "base/error.h"
#include "sources/readers/detail/axes.h"

namespace voxlink::sources {

struct DicomSlice {
  std::string path;
  uint32_t frame = 0;       // frame index inside the file (0 for single-frame files)
  uint32_t fileFrames = 1;  // NumberOfFrames of the file
  Vec3 position{0, 0, 0};   // ImagePositionPatient (or the frame's PlanePositionSequence)
  double along = 0;         // position . slice normal
  int64_t instance = 0;     // InstanceNumber (0 when absent)
  double slope = 1;         // RescaleSlope, or DoseGridScaling
  double intercept = 0;     // RescaleIntercept
  // Explicit VR Big Endian: where this frame's bytes start in the file. They are read and
  // swapped here, not by GDCM, whose readers leave 32-bit values unswapped or half-swapped.
  uint64_t bigEndianPixelsAt = 0;
  bool inflateWholeFile = false;  // deflated multi-frame: GDCM's frame reader cannot inflate
  // Signed pixels from a codec (JPEG-LS, JPEG 2000) that may return BitsStored-bit patterns.
  bool extendSign = false;
};

// "CTHead7.dcm", or "dose.dcm frame 3" (frames counted from 1) for errors and notes.
std::string sliceName(const DicomSlice& slice);

struct DicomFileHeader {
  std::string path;
  bool image = false;  // false: a DICOM file without pixel data (report, RT structures, ...)
  std::string series, modality, description;
  uint32_t rows = 0, columns = 0;
  int bitsAllocated = 0, bitsStored = 0, pixelRepresentation = 0;
  std::string photometric;
  std::string transferSyntax;    // TransferSyntaxUID (0002,0010)
  bool modalityLut = false;      // a Modality LUT Sequence (0028,3000), not applied
  bool hasPosition = false;      // positions came from the file
  bool hasOrientation = false;   // otherwise +x, +y
  bool hasPixelSpacing = false;  // otherwise 1 1
  std::array<double, 6> orientation{1, 0, 0, 0, 1, 0};
  std::array<double, 2> pixelSpacing{1, 1};
  double sliceThickness = 0, spacingBetweenSlices = 0;  // 0: absent
  std::string rescaleField;        // "RescaleSlope/RescaleIntercept", "DoseGridScaling", or empty
  std::string positionField;       // where the positions came from, for notes
  std::vector<DicomSlice> frames;  // one per frame, in file order
};

// Reads the header up to the pixel data (deflated files: the whole file). Not an image: `image`
// false, no error. Errors name the file and the tag: kUnsupported (color, odd bit depths,
// transfer syntaxes GDCM cannot decode), kCorrupt (malformed values, per-frame
// groups that disagree with NumberOfFrames, frames with different orientations), kTruncated
// (uncompressed pixel data shorter than Rows x Columns x BitsAllocated x NumberOfFrames).
Result<DicomFileHeader> readDicomFileHeader(const std::string& file);

}  // namespace voxlink::sources
