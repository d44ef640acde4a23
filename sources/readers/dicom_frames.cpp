// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/dicom_frames.h"

#include <cmath>

#include "sources/readers/detail/dicom_tags.h"

namespace voxlink::sources {
namespace {

constexpr const char* kEnhancedCt = "1.2.840.10008.5.1.4.1.1.2.1";
constexpr const char* kEnhancedMr = "1.2.840.10008.5.1.4.1.1.4.1";

Vec3 sliceNormal(const std::array<double, 6>& o) {
  Vec3 n = cross({o[0], o[1], o[2]}, {o[3], o[4], o[5]});
  const double len = length(n);
  if (len > 0)
    for (double& c : n) c /= len;
  return n;
}

// RT Dose: frame k lies at ImagePositionPatient + offset[k] along the normal. The standard
// allows offsets relative to the first frame (offset[0] = 0) or absolute along the normal;
// both are taken relative to offset[0].
Status rtDoseFrames(const gdcm::DataSet& ds, const DicomSlice& first, DicomFileHeader& h) {
  const uint32_t frames = first.fileFrames;
  VOXLINK_ASSIGN_OR_RETURN(
      std::vector<double> offsets,
      decimals(ds, 0x3004, 0x000c, h.path, "GridFrameOffsetVector (3004,000C)", 0));
  if (offsets.size() != frames)
    return makeError(ErrorCode::kCorrupt, h.path,
                     ": tag GridFrameOffsetVector (3004,000C): ", offsets.size(),
                     " offsets, NumberOfFrames (0028,0008) says ", frames);
  if (!h.hasPosition)
    return makeError(ErrorCode::kCorrupt, h.path,
                     ": tag ImagePositionPatient (0020,0032) missing; GridFrameOffsetVector ",
                     "(3004,000C) is relative to it");
  const Vec3 n = sliceNormal(h.orientation);
  h.positionField = "ImagePositionPatient + GridFrameOffsetVector";
  for (uint32_t k = 0; k < frames; ++k) {
    DicomSlice s = first;
    s.frame = k;
    s.instance = k + 1;
    const double d = offsets[k] - offsets[0];
    for (int a = 0; a < 3; ++a) s.position[a] = first.position[a] + d * n[a];
    h.frames.push_back(s);
  }
  return Status::ok();
}

// Reads one frame's functional groups into `s` and, for the first frame, into `h`; later
// frames must agree with the first on orientation and pixel spacing.
Status enhancedFrame(const gdcm::DataSet* perFrame, const gdcm::DataSet* shared, uint32_t k,
                     DicomSlice& s, DicomFileHeader& h, bool& anyPosition, bool& allPositions) {
  const std::string& file = h.path;
  const std::string where = cat(" (frame ", k + 1, ")");
  if (auto g = functionalGroup(perFrame, shared, 0x0020, 0x9113)) {
    VOXLINK_ASSIGN_OR_RETURN(
        auto ipp,
        decimals(*g, 0x0020, 0x0032, file,
                 "PlanePositionSequence (0020,9113) ImagePositionPatient (0020,0032)", 3));
    s.position = {ipp[0], ipp[1], ipp[2]};
    anyPosition = true;
  } else {
    allPositions = false;
  }
  if (auto g = functionalGroup(perFrame, shared, 0x0020, 0x9116)) {
    VOXLINK_ASSIGN_OR_RETURN(
        auto iop,
        decimals(*g, 0x0020, 0x0037, file,
                 "PlaneOrientationSequence (0020,9116) ImageOrientationPatient (0020,0037)", 6));
    if (k == 0 || !h.hasOrientation) {
      std::copy(iop.begin(), iop.end(), h.orientation.begin());
      h.hasOrientation = true;
    }
    for (int i = 0; i < 6; ++i)
      if (std::fabs(iop[i] - h.orientation[i]) > 1e-4)
        return makeError(ErrorCode::kUnsupported, file,
                         ": tag PlaneOrientationSequence (0020,9116): frame ", k + 1,
                         " has orientation ", iop[0], "\\", iop[1], "\\", iop[2], "\\", iop[3],
                         "\\", iop[4], "\\", iop[5], ", frame 1 ", h.orientation[0], "\\",
                         h.orientation[1], "\\", h.orientation[2], "\\", h.orientation[3], "\\",
                         h.orientation[4], "\\", h.orientation[5], " (mixed orientations)");
  }
  if (auto g = functionalGroup(perFrame, shared, 0x0028, 0x9110)) {
    VOXLINK_ASSIGN_OR_RETURN(
        auto ps, decimals(*g, 0x0028, 0x0030, file,
                          "PixelMeasuresSequence (0028,9110) PixelSpacing (0028,0030)", 2));
    if (k == 0 || !h.hasPixelSpacing) {
      h.pixelSpacing = {ps[0], ps[1]};
      h.hasPixelSpacing = true;
    }
    for (int i = 0; i < 2; ++i)
      if (std::fabs(ps[i] - h.pixelSpacing[i]) > 1e-4 * std::fabs(h.pixelSpacing[i]))
        return makeError(ErrorCode::kUnsupported, file,
                         ": tag PixelMeasuresSequence (0028,9110): frame ", k + 1,
                         " has PixelSpacing ", ps[0], "\\", ps[1], ", frame 1 ", h.pixelSpacing[0],
                         "\\", h.pixelSpacing[1]);
    if (k == 0) {
      VOXLINK_ASSIGN_OR_RETURN(
          auto t, optionalDecimals(*g, 0x0018, 0x0050, file, "SliceThickness (0018,0050)", 1));
      VOXLINK_ASSIGN_OR_RETURN(auto b, optionalDecimals(*g, 0x0018, 0x0088, file,
                                                        "SpacingBetweenSlices (0018,0088)", 1));
      if (t) h.sliceThickness = (*t)[0];
      if (b) h.spacingBetweenSlices = (*b)[0];
    }
  }
  if (auto g = functionalGroup(perFrame, shared, 0x0028, 0x9145)) {
    const char* slopeName = "PixelValueTransformationSequence (0028,9145) RescaleSlope (0028,1053)";
    const char* interceptName =
        "PixelValueTransformationSequence (0028,9145) RescaleIntercept (0028,1052)";
    VOXLINK_ASSIGN_OR_RETURN(auto slope, optionalDecimals(*g, 0x0028, 0x1053, file, slopeName, 1));
    VOXLINK_ASSIGN_OR_RETURN(auto icpt,
                             optionalDecimals(*g, 0x0028, 0x1052, file, interceptName, 1));
    if (slope) s.slope = (*slope)[0];
    if (icpt) s.intercept = (*icpt)[0];
    if (slope || icpt) h.rescaleField = "RescaleSlope/RescaleIntercept";
    if (!std::isfinite(s.slope) || s.slope == 0 || !std::isfinite(s.intercept))
      return makeError(ErrorCode::kCorrupt, file, ": tag PixelValueTransformationSequence ",
                       "(0028,9145)", where, ": slope ", s.slope, ", intercept ", s.intercept,
                       " (expected finite numbers, slope not 0)");
  }
  return Status::ok();
}

Status enhancedFrames(const DicomSlice& first, DicomFileHeader& h,
                      const std::vector<gdcm::DataSet>& perFrame,
                      const std::vector<gdcm::DataSet>& shared) {
  const uint32_t frames = first.fileFrames;
  if (perFrame.size() != frames)
    return makeError(ErrorCode::kCorrupt, h.path,
                     ": tag PerFrameFunctionalGroupsSequence (5200,9230): ", perFrame.size(),
                     " items, NumberOfFrames (0028,0008) says ", frames);
  const gdcm::DataSet* sharedItem = shared.empty() ? nullptr : &shared.front();
  bool anyPosition = false, allPositions = true;
  for (uint32_t k = 0; k < frames; ++k) {
    DicomSlice s = first;
    s.frame = k;
    s.instance = k + 1;
    VOXLINK_RETURN_IF_ERROR(
        enhancedFrame(&perFrame[k], sharedItem, k, s, h, anyPosition, allPositions));
    h.frames.push_back(s);
  }
  if (anyPosition && !allPositions)
    return makeError(ErrorCode::kCorrupt, h.path,
                     ": tag PlanePositionSequence (0020,9113): some frames have a position, ",
                     "others none");
  if (anyPosition) {
    h.hasPosition = true;
    h.positionField = "PlanePositionSequence";
  }
  return Status::ok();
}

}  // namespace

Status readFrames(const gdcm::DataSet& ds, const DicomSlice& first, DicomFileHeader& h) {
  const auto perFrame = sequenceItems(ds, 0x5200, 0x9230);
  const auto shared = sequenceItems(ds, 0x5200, 0x9229);
  const std::string sopClass = stringValue(ds, 0x0008, 0x0016);
  const bool enhanced = sopClass == kEnhancedCt || sopClass == kEnhancedMr;
  if (!perFrame.empty() || !shared.empty()) return enhancedFrames(first, h, perFrame, shared);
  if (enhanced)
    return makeError(ErrorCode::kCorrupt, h.path,
                     ": tag PerFrameFunctionalGroupsSequence (5200,9230) missing (an Enhanced ",
                     sopClass == kEnhancedCt ? "CT" : "MR", " image must have it)");
  if (first.fileFrames > 1 && h.modality == "RTDOSE") return rtDoseFrames(ds, first, h);
  // One frame, or frames without positions of their own: they share the image's values.
  if (first.fileFrames > 1) {
    h.hasPosition = false;
    h.positionField.clear();
  }
  for (uint32_t k = 0; k < first.fileFrames; ++k) {
    DicomSlice s = first;
    s.frame = k;
    if (first.fileFrames > 1) s.instance = k + 1;
    h.frames.push_back(s);
  }
  return Status::ok();
}

}  // namespace voxlink::sources
