// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/dicom_reader.h"

#include <gdcmBoxRegion.h>
#include <gdcmImageRegionReader.h>
#include <gdcmPixmapReader.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <set>
#include <vector>

#include "sources/readers/detail/dicom_pixel_encoding.h"
#include "sources/readers/detail/gdcm_messages.h"
#include "sources/readers/detail/rescale.h"
#include "sources/readers/dicom_series.h"
#include "sources/readers/reader_common.h"

namespace voxlink::sources {
namespace {

class DicomSource final : public VolumeSource {
 public:
  DicomSource(VolumeInfo info, DicomSeries series, bool rescale)
      : series_(std::move(series)), rescale_(rescale) {
    info_ = std::move(info);
  }

  bool randomAccess() const override { return true; }

  Status read(uint32_t z0, uint32_t count, void* dst) override {
    VOXLINK_RETURN_IF_ERROR(checkSliceRange(z0, count));
    const uint64_t storedBytes = info_.sliceVoxels() * scalarSize(series_.storedType);
    auto* out = static_cast<uint8_t*>(dst);
    for (uint32_t z = z0; z < z0 + count; ++z) {
      const DicomSlice& slice = series_.slices[z];
      uint8_t* target = out + uint64_t{z - z0} * info_.sliceBytes();
      if (rescale_) scratch_.resize(storedBytes);
      uint8_t* pixels = rescale_ ? scratch_.data() : target;
      int decodedBits = series_.bitsStored;
      if (slice.bigEndianPixelsAt)
        VOXLINK_RETURN_IF_ERROR(readBigEndian(slice, pixels, storedBytes));
      else if (slice.inflateWholeFile)
        VOXLINK_RETURN_IF_ERROR(readInflatedFrame(slice, pixels, storedBytes));
      else if (slice.fileFrames > 1)
        VOXLINK_RETURN_IF_ERROR(readFrame(slice, pixels, storedBytes));
      else
        VOXLINK_RETURN_IF_ERROR(readPixels(slice.path, pixels, storedBytes, decodedBits));
      // A codestream holding more bits than BitsStored (GDCM reads its precision) is signed.
      if (slice.extendSign && decodedBits <= series_.bitsStored)
        extendSign(pixels, series_.storedType, info_.sliceVoxels(), series_.bitsStored);
      if (rescale_)
        convertRescaled(scratch_.data(), series_.storedType, target, info_.type,
                        info_.sliceVoxels(), slice.slope, slice.intercept);
    }
    return Status::ok();
  }

 private:
  // Native big-endian pixels, straight from the file: each value's bytes reversed.
  Status readBigEndian(const DicomSlice& slice, uint8_t* dst, uint64_t bytes) {
    std::ifstream in(slice.path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(slice.bigEndianPixelsAt));
    in.read(reinterpret_cast<char*>(dst), static_cast<std::streamsize>(bytes));
    if (!in || static_cast<uint64_t>(in.gcount()) != bytes)
      return makeError(ErrorCode::kTruncated, slice.path, ": tag PixelData (7FE0,0010): frame ",
                       slice.frame + 1, " ends past the end of the file");
    swapEachValue(dst, scalarSize(series_.storedType), bytes / scalarSize(series_.storedType));
    return Status::ok();
  }

  // A frame of a deflated multi-frame file: GDCM inflates the whole file; its pixels are kept
  // while frames come from the same file (deflated files are small: zlib on the whole data set).
  Status readInflatedFrame(const DicomSlice& slice, uint8_t* dst, uint64_t bytes) {
    if (inflatedPath_ != slice.path) {
      inflatedPath_.clear();
      int decodedBits = 0;
      inflated_.resize(bytes * slice.fileFrames);
      VOXLINK_RETURN_IF_ERROR(
          readPixels(slice.path, inflated_.data(), inflated_.size(), decodedBits));
      inflatedPath_ = slice.path;
    }
    std::memcpy(dst, inflated_.data() + uint64_t{slice.frame} * bytes, bytes);
    return Status::ok();
  }

  // One frame of a multi-frame file, decoded alone (GDCM's region reader decodes only the
  // fragments of that frame), so memory stays at the slices asked for. The file's header is
  // parsed once while consecutive frames come from the same file.
  Status readFrame(const DicomSlice& slice, uint8_t* dst, uint64_t bytes) {
    GdcmMessages messages;
    if (!frameReader_ || framePath_ != slice.path) {
      frameReader_ = std::make_unique<gdcm::ImageRegionReader>();
      framePath_.clear();
      frameReader_->SetFileName(slice.path.c_str());
      if (!frameReader_->ReadInformation())
        return makeError(ErrorCode::kCorrupt, slice.path, ": GDCM cannot read the image",
                         messages.reason());
      framePath_ = slice.path;
    }
    gdcm::BoxRegion box;
    box.SetDomain(0, info_.dims[0] - 1, 0, info_.dims[1] - 1, slice.frame, slice.frame);
    frameReader_->SetRegion(box);
    if (frameReader_->ComputeBufferLength() != bytes)
      return makeError(ErrorCode::kSizeMismatch, slice.path, ": tag PixelData (7FE0,0010): frame ",
                       slice.frame + 1, " is ", frameReader_->ComputeBufferLength(),
                       " bytes, expected ", bytes);
    if (!frameReader_->ReadIntoBuffer(reinterpret_cast<char*>(dst), bytes)) {
      framePath_.clear();
      return makeError(ErrorCode::kCorrupt, slice.path, ": tag PixelData (7FE0,0010): GDCM ",
                       "cannot decode frame ", slice.frame + 1, messages.reason());
    }
    return Status::ok();
  }

  // The whole pixel data of a file. The pixmap reader, not the image reader: that one also
  // reads geometry GDCM asserts on (an RT Dose without NumberOfFrames aborts it). `decodedBits`:
  // the bits per sample GDCM found in the codestream.
  Status readPixels(const std::string& file, uint8_t* dst, uint64_t bytes, int& decodedBits) {
    gdcm::PixmapReader reader;
    reader.SetFileName(file.c_str());
    GdcmMessages messages;
    if (!reader.Read())
      return makeError(ErrorCode::kCorrupt, file, ": GDCM cannot read the image",
                       messages.reason());
    const gdcm::Pixmap& image = reader.GetPixmap();
    if (image.GetColumns() != info_.dims[0] || image.GetRows() != info_.dims[1])
      return makeError(ErrorCode::kSizeMismatch, file, ": pixel data is ", image.GetColumns(), "x",
                       image.GetRows(), ", the series is ", info_.dims[0], "x", info_.dims[1]);
    if (image.GetBufferLength() != bytes)
      return makeError(ErrorCode::kSizeMismatch, file,
                       ": tag PixelData (7FE0,0010): ", image.GetBufferLength(), " bytes decoded, ",
                       bytes, " expected");
    if (!image.GetBuffer(reinterpret_cast<char*>(dst)))
      return makeError(ErrorCode::kCorrupt, file,
                       ": tag PixelData (7FE0,0010): GDCM cannot decode it", messages.reason());
    decodedBits = image.GetPixelFormat().GetBitsStored();
    return Status::ok();
  }

  DicomSeries series_;
  bool rescale_;
  std::vector<uint8_t> scratch_;
  std::unique_ptr<gdcm::ImageRegionReader> frameReader_;
  std::string framePath_;  // the file frameReader_ has read the header of
  std::vector<uint8_t> inflated_;
  std::string inflatedPath_;  // the deflated file inflated_ holds the pixels of
};

bool integral(double v) { return std::isfinite(v) && v == std::floor(v); }

}  // namespace

Result<std::unique_ptr<VolumeSource>> openDicomSeriesDirect(const std::string& dir,
                                                            const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(DicomSeries series, scanDicomSeries(dir, options.dicomSeries));
  const std::array<uint64_t, 3> dims{series.columns, series.rows, series.slices.size()};
  VOXLINK_RETURN_IF_ERROR(checkDims(dims, dir, "Columns Rows slices"));

  VolumeInfo info;
  info.path = dir;
  info.format = "dicom";
  for (int a = 0; a < 3; ++a) info.dims[a] = static_cast<uint32_t>(dims[a]);
  info.spacing = {series.columnSpacing, series.rowSpacing, series.sliceSpacing};
  info.origin = series.origin;
  info.notes = series.notes;
  std::set<std::string> seen;  // a multi-frame file holds several slices
  for (const DicomSlice& slice : series.slices)
    if (seen.insert(slice.path).second) info.files.push_back(slice.path);
  const AxesSummary axes = summarizeAxes(
      {series.rowDirection, series.columnDirection, series.normal}, "ImageOrientationPatient axes");
  if (!axes.note.empty()) info.notes.push_back(axes.note);

  // Rescale: the value range of BitsStored through every slice's slope and intercept.
  const bool isSigned = voxlink::isSigned(series.storedType);
  const double storedMin = isSigned ? -std::ldexp(1.0, series.bitsStored - 1) : 0.0;
  const double storedMax = isSigned ? std::ldexp(1.0, series.bitsStored - 1) - 1
                                    : std::ldexp(1.0, series.bitsStored) - 1;
  bool identity = true, allIntegral = true;
  double lo = 0, hi = 0, minSlope = 0, maxSlope = 0, minIntercept = 0, maxIntercept = 0;
  for (size_t i = 0; i < series.slices.size(); ++i) {
    const DicomSlice& s = series.slices[i];
    identity = identity && s.slope == 1 && s.intercept == 0;
    allIntegral = allIntegral && integral(s.slope) && integral(s.intercept);
    const double a = storedMin * s.slope + s.intercept, b = storedMax * s.slope + s.intercept;
    lo = i ? std::min({lo, a, b}) : std::min(a, b);
    hi = i ? std::max({hi, a, b}) : std::max(a, b);
    minSlope = i ? std::min(minSlope, s.slope) : s.slope;
    maxSlope = i ? std::max(maxSlope, s.slope) : s.slope;
    minIntercept = i ? std::min(minIntercept, s.intercept) : s.intercept;
    maxIntercept = i ? std::max(maxIntercept, s.intercept) : s.intercept;
  }
  info.type =
      identity ? series.storedType : typeForValueRange(series.storedType, lo, hi, allIntegral);
  if (!identity) {
    const bool uniform = minSlope == maxSlope && minIntercept == maxIntercept;
    const std::string& field = series.rescaleField;
    info.notes.push_back(
        uniform
            ? cat(field, " applied: value = stored ", scalarName(series.storedType), " * ",
                  minSlope, " + ", minIntercept, ", served as ", scalarName(info.type))
            : cat(field, " applied per slice (slopes ", minSlope, "..", maxSlope, ", intercepts ",
                  minIntercept, "..", maxIntercept, "), served as ", scalarName(info.type)));
    info.rescale = SourceRescale{field,        std::string(scalarName(series.storedType)),
                                 minSlope,     maxSlope,
                                 minIntercept, maxIntercept};
  }
  VOXLINK_RETURN_IF_ERROR(applyOpenOptions(info, options));
  return std::unique_ptr<VolumeSource>(
      new DicomSource(std::move(info), std::move(series), !identity));
}

}  // namespace voxlink::sources
