// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/dicom_header.h"

#include <gdcmReader.h>

#include <cmath>
#include <filesystem>

#include "base/limits.h"
#include "sources/readers/detail/dicom_frames.h"
#include "sources/readers/detail/dicom_pixel_encoding.h"
#include "sources/readers/detail/dicom_tags.h"
#include "sources/readers/detail/gdcm_messages.h"
#include "sources/readers/detail/text_header.h"

namespace voxlink::sources {
namespace {

namespace fs = std::filesystem;

Result<uint32_t> frameCount(const gdcm::DataSet& ds, const std::string& file) {
  const std::string text = stringValue(ds, 0x0028, 0x0008);
  if (text.empty()) return 1u;
  VOXLINK_ASSIGN_OR_RETURN(int64_t n, parseInteger(text, file, "NumberOfFrames (0028,0008)"));
  if (n < 1 || n > static_cast<int64_t>(limits::kMaxAxis))
    return makeError(ErrorCode::kCorrupt, file, ": tag NumberOfFrames (0028,0008): ", n,
                     ", expected 1..", limits::kMaxAxis);
  return static_cast<uint32_t>(n);
}

// Image-level geometry and rescale of a classic (not Enhanced) file; per-frame values, when the
// file has them, replace these in readFrames().
Status readClassicGeometry(const gdcm::DataSet& ds, DicomFileHeader& h, DicomSlice& first) {
  const std::string& file = h.path;
  VOXLINK_ASSIGN_OR_RETURN(
      auto ipp, optionalDecimals(ds, 0x0020, 0x0032, file, "ImagePositionPatient (0020,0032)", 3));
  VOXLINK_ASSIGN_OR_RETURN(auto iop, optionalDecimals(ds, 0x0020, 0x0037, file,
                                                      "ImageOrientationPatient (0020,0037)", 6));
  VOXLINK_ASSIGN_OR_RETURN(
      auto ps, optionalDecimals(ds, 0x0028, 0x0030, file, "PixelSpacing (0028,0030)", 2));
  VOXLINK_ASSIGN_OR_RETURN(
      auto thickness, optionalDecimals(ds, 0x0018, 0x0050, file, "SliceThickness (0018,0050)", 1));
  VOXLINK_ASSIGN_OR_RETURN(auto between, optionalDecimals(ds, 0x0018, 0x0088, file,
                                                          "SpacingBetweenSlices (0018,0088)", 1));
  if (ipp) {
    h.hasPosition = true;
    h.positionField = "ImagePositionPatient";
    first.position = {(*ipp)[0], (*ipp)[1], (*ipp)[2]};
  }
  if (iop) {
    h.hasOrientation = true;
    std::copy(iop->begin(), iop->end(), h.orientation.begin());
  }
  if (ps) {
    h.hasPixelSpacing = true;
    h.pixelSpacing = {(*ps)[0], (*ps)[1]};
  }
  if (thickness) h.sliceThickness = (*thickness)[0];
  if (between) h.spacingBetweenSlices = (*between)[0];

  if (h.modality == "RTDOSE") {
    VOXLINK_ASSIGN_OR_RETURN(
        auto scaling, optionalDecimals(ds, 0x3004, 0x000e, file, "DoseGridScaling (3004,000E)", 1));
    if (scaling) {
      h.rescaleField = "DoseGridScaling";
      first.slope = (*scaling)[0];
    }
  }
  if (h.rescaleField.empty()) {
    VOXLINK_ASSIGN_OR_RETURN(
        auto slope, optionalDecimals(ds, 0x0028, 0x1053, file, "RescaleSlope (0028,1053)", 1));
    VOXLINK_ASSIGN_OR_RETURN(auto intercept, optionalDecimals(ds, 0x0028, 0x1052, file,
                                                              "RescaleIntercept (0028,1052)", 1));
    if (slope) first.slope = (*slope)[0];
    if (intercept) first.intercept = (*intercept)[0];
    if (slope || intercept) h.rescaleField = "RescaleSlope/RescaleIntercept";
  }
  const std::string instance = stringValue(ds, 0x0020, 0x0013);
  if (!instance.empty()) {
    auto n = parseInteger(instance, file, "InstanceNumber (0020,0013)");
    if (n) first.instance = *n;
  }
  return Status::ok();
}

}  // namespace

std::string sliceName(const DicomSlice& slice) {
  const std::string name = fs::path(slice.path).filename().string();
  return slice.fileFrames > 1 ? cat(name, " frame ", slice.frame + 1) : name;
}

Result<DicomFileHeader> readDicomFileHeader(const std::string& file) {
  gdcm::Reader upToPixels, whole;
  gdcm::Reader* reader = &upToPixels;
  upToPixels.SetFileName(file.c_str());
  const gdcm::Tag pixelData(0x7fe0, 0x0010);
  GdcmMessages messages;
  if (!upToPixels.ReadUpToTag(pixelData, {pixelData})) {
    const std::string uid = transferSyntaxUid(upToPixels.GetFile().GetHeader());
    VOXLINK_RETURN_IF_ERROR(checkPixelEncoding(gdcm::DataSet(), uid, file));
    // GDCM cannot always stop inside a deflated stream: read the file whole.
    whole.SetFileName(file.c_str());
    if (!isDeflatedSyntax(uid) || !whole.Read())
      return makeError(ErrorCode::kCorrupt, file, ": GDCM cannot parse this DICOM file",
                       messages.reason());
    reader = &whole;
  }
  const gdcm::DataSet& ds = reader->GetFile().GetDataSet();
  const size_t pixelDataAt = reader->GetStreamCurrentPosition();
  DicomFileHeader h;
  h.path = file;
  h.transferSyntax = transferSyntaxUid(reader->GetFile().GetHeader());
  h.series = stringValue(ds, 0x0020, 0x000e);
  h.modality = stringValue(ds, 0x0008, 0x0060);
  h.description = stringValue(ds, 0x0008, 0x103e);
  const auto rows = ushortValue<0x0028, 0x0010>(ds);
  const auto columns = ushortValue<0x0028, 0x0011>(ds);
  const auto bitsAllocated = ushortValue<0x0028, 0x0100>(ds);
  if (!rows || !columns || !bitsAllocated) return h;  // no image: a report, RT structures, ...
  h.image = true;
  if (*rows == 0 || *columns == 0)
    return makeError(ErrorCode::kCorrupt, file, ": tag Rows x Columns (0028,0010/0011): ", *columns,
                     "x", *rows);
  VOXLINK_RETURN_IF_ERROR(checkPixelEncoding(ds, h.transferSyntax, file));
  h.rows = *rows;
  h.columns = *columns;
  h.bitsAllocated = *bitsAllocated;
  h.bitsStored = ushortValue<0x0028, 0x0101>(ds).value_or(*bitsAllocated);
  h.pixelRepresentation = ushortValue<0x0028, 0x0103>(ds).value_or(0);
  h.modalityLut = ds.FindDataElement(gdcm::Tag(0x0028, 0x3000));
  VOXLINK_ASSIGN_OR_RETURN(const uint32_t frames, frameCount(ds, file));
  // Uncompressed pixel data must all be there: GDCM reads a file cut inside it without a word.
  // (A deflated file's size says nothing about it: GDCM has inflated the whole file above.)
  const bool deflated = isDeflatedSyntax(h.transferSyntax);
  const uint64_t frameBytes = uint64_t{*rows} * *columns * (*bitsAllocated / 8);
  if (!isEncapsulatedSyntax(h.transferSyntax) && !deflated) {
    const uint64_t need = frameBytes * frames;
    const uint64_t start = pixelDataAt;  // ReadUpToTag stops after the element's tag and length
    std::error_code ec;
    const uint64_t size = fs::file_size(file, ec);
    if (!ec && size < start + need)
      return makeError(ErrorCode::kTruncated, file, ": tag PixelData (7FE0,0010): the file holds ",
                       size > start ? size - start : 0, " bytes of pixel data, Rows x Columns x ",
                       "BitsAllocated", frames > 1 ? " x NumberOfFrames" : "", " need ", need);
  }
  h.photometric = stringValue(ds, 0x0028, 0x0004);
  DicomSlice first;
  first.path = file;
  first.fileFrames = frames;
  VOXLINK_RETURN_IF_ERROR(readClassicGeometry(ds, h, first));
  if (!std::isfinite(first.slope) || first.slope == 0 || !std::isfinite(first.intercept))
    return makeError(ErrorCode::kCorrupt, file, ": tag ", h.rescaleField, ": slope ", first.slope,
                     ", intercept ", first.intercept, " (expected finite numbers, slope not 0)");
  VOXLINK_RETURN_IF_ERROR(readFrames(ds, first, h));
  for (DicomSlice& s : h.frames) {
    if (isBigEndianSyntax(h.transferSyntax))
      s.bigEndianPixelsAt = pixelDataAt + s.frame * frameBytes;
    s.inflateWholeFile = deflated && frames > 1;
    s.extendSign = h.pixelRepresentation == 1 && isEncapsulatedSyntax(h.transferSyntax) &&
                   h.bitsStored < h.bitsAllocated;
  }
  return h;
}

}  // namespace voxlink::sources
