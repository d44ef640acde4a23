#include "sources/readers/dicom_series.h"

#include <gdcmAttribute.h>
#include <gdcmReader.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

#include "sources/readers/dicom_probe.h"
#include "sources/readers/file_list.h"
#include "sources/readers/gdcm_guard.h"
#include "sources/readers/gdcm_messages.h"
#include "sources/readers/reader_common.h"
#include "sources/readers/text_header.h"

namespace voxlink::convert {
namespace {

namespace fs = std::filesystem;

// The text of a string-valued element (DS, IS, UI, CS), or empty when absent.
std::string stringValue(const gdcm::DataSet& ds, uint16_t group, uint16_t element) {
  const gdcm::Tag tag(group, element);
  if (!ds.FindDataElement(tag)) return {};
  const gdcm::ByteValue* bv = ds.GetDataElement(tag).GetByteValue();
  if (!bv) return {};
  std::string s(bv->GetPointer(), bv->GetLength());
  while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) s.pop_back();
  return std::string(trim(s));
}

// Backslash-separated decimal values ("0.5\0.5").
Result<std::vector<double>> decimals(const gdcm::DataSet& ds, uint16_t group, uint16_t element,
                                     const std::string& file, const char* name, size_t count) {
  std::string text = stringValue(ds, group, element);
  if (text.empty()) return makeError(ErrorCode::kUnsupported, file, ": tag ", name, " missing");
  std::replace(text.begin(), text.end(), '\\', ' ');
  return parseDoubles(text, file, name, count);
}

template <uint16_t G, uint16_t E>
std::optional<uint16_t> ushortValue(const gdcm::DataSet& ds) {
  gdcm::Attribute<G, E> at;
  if (!ds.FindDataElement(at.GetTag()) || ds.GetDataElement(at.GetTag()).IsEmpty())
    return std::nullopt;
  at.SetFromDataSet(ds);
  return static_cast<uint16_t>(at.GetValue());
}

struct SliceHeader {
  DicomSlice slice;
  std::string series;
  uint32_t rows = 0, columns = 0;
  int bitsAllocated = 0, bitsStored = 0, pixelRepresentation = 0;
  std::string photometric;
  std::array<double, 6> orientation{};
  std::array<double, 2> pixelSpacing{};
};

Result<SliceHeader> readSliceHeader(const std::string& file) {
  gdcm::Reader reader;
  reader.SetFileName(file.c_str());
  const gdcm::Tag pixelData(0x7fe0, 0x0010);
  GdcmMessages messages;
  if (!reader.ReadUpToTag(pixelData, {pixelData}))
    return makeError(ErrorCode::kCorrupt, file, ": GDCM cannot parse this DICOM file",
                     messages.reason());
  const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
  const size_t pixelDataAt = reader.GetStreamCurrentPosition();
  const gdcm::TransferSyntax& syntax = reader.GetFile().GetHeader().GetDataSetTransferSyntax();
  SliceHeader h;
  h.slice.path = file;
  h.series = stringValue(ds, 0x0020, 0x000e);
  const auto rows = ushortValue<0x0028, 0x0010>(ds);
  const auto columns = ushortValue<0x0028, 0x0011>(ds);
  const auto bitsAllocated = ushortValue<0x0028, 0x0100>(ds);
  if (!rows || !columns || !bitsAllocated || *rows == 0 || *columns == 0)
    return makeError(
        ErrorCode::kUnsupported, file,
        ": tag Rows/Columns/BitsAllocated (0028,0010/0011/0100) missing; not an image");
  h.rows = *rows;
  h.columns = *columns;
  h.bitsAllocated = *bitsAllocated;
  h.bitsStored = ushortValue<0x0028, 0x0101>(ds).value_or(*bitsAllocated);
  h.pixelRepresentation = ushortValue<0x0028, 0x0103>(ds).value_or(0);
  const int samples = ushortValue<0x0028, 0x0002>(ds).value_or(1);
  if (samples != 1)
    return makeError(ErrorCode::kUnsupported, file, ": tag SamplesPerPixel (0028,0002): ", samples,
                     " (only single-channel images)");
  const std::string frames = stringValue(ds, 0x0028, 0x0008);
  if (!frames.empty() && frames != "1")
    return makeError(ErrorCode::kUnsupported, file, ": tag NumberOfFrames (0028,0008): ", frames,
                     " (multi-frame files are not supported)");
  // Uncompressed pixel data must all be there: GDCM reads a file cut inside it without a word.
  if (!syntax.IsEncapsulated() && *bitsAllocated % 8 == 0) {
    const uint64_t need = uint64_t{*rows} * *columns * (*bitsAllocated / 8);
    const uint64_t start = pixelDataAt;  // ReadUpToTag stops after the element's tag and length
    std::error_code ec;
    const uint64_t size = fs::file_size(file, ec);
    if (!ec && size < start + need)
      return makeError(ErrorCode::kTruncated, file, ": tag PixelData (7FE0,0010): the file holds ",
                       size > start ? size - start : 0,
                       " bytes of pixel data, Rows x Columns x BitsAllocated need ", need);
  }
  h.photometric = stringValue(ds, 0x0028, 0x0004);
  VOXLINK_ASSIGN_OR_RETURN(
      std::vector<double> ipp,
      decimals(ds, 0x0020, 0x0032, file, "ImagePositionPatient (0020,0032)", 3));
  VOXLINK_ASSIGN_OR_RETURN(
      std::vector<double> iop,
      decimals(ds, 0x0020, 0x0037, file, "ImageOrientationPatient (0020,0037)", 6));
  VOXLINK_ASSIGN_OR_RETURN(std::vector<double> ps,
                           decimals(ds, 0x0028, 0x0030, file, "PixelSpacing (0028,0030)", 2));
  h.slice.position = {ipp[0], ipp[1], ipp[2]};
  std::copy(iop.begin(), iop.end(), h.orientation.begin());
  h.pixelSpacing = {ps[0], ps[1]};
  if (!stringValue(ds, 0x0028, 0x1053).empty()) {
    VOXLINK_ASSIGN_OR_RETURN(std::vector<double> s,
                             decimals(ds, 0x0028, 0x1053, file, "RescaleSlope (0028,1053)", 1));
    h.slice.slope = s[0];
  }
  if (!stringValue(ds, 0x0028, 0x1052).empty()) {
    VOXLINK_ASSIGN_OR_RETURN(std::vector<double> i,
                             decimals(ds, 0x0028, 0x1052, file, "RescaleIntercept (0028,1052)", 1));
    h.slice.intercept = i[0];
  }
  if (!std::isfinite(h.slice.slope) || h.slice.slope == 0)
    return makeError(ErrorCode::kCorrupt, file, ": tag RescaleSlope (0028,1053): ", h.slice.slope);
  const std::string instance = stringValue(ds, 0x0020, 0x0013);
  if (!instance.empty()) {
    auto n = parseInteger(instance, file, "InstanceNumber (0020,0013)");
    if (n) h.slice.instance = *n;
  }
  return h;
}

Result<ScalarType> storedType(const SliceHeader& h) {
  const bool s = h.pixelRepresentation == 1;
  switch (h.bitsAllocated) {
    case 8:
      return s ? ScalarType::kI8 : ScalarType::kU8;
    case 16:
      return s ? ScalarType::kI16 : ScalarType::kU16;
    case 32:
      return s ? ScalarType::kI32 : ScalarType::kU32;
    default:
      return makeError(ErrorCode::kUnsupported, h.slice.path,
                       ": tag BitsAllocated (0028,0100): ", h.bitsAllocated,
                       " (8, 16 or 32 are supported)");
  }
}

Status checkSameGeometry(const SliceHeader& first, const SliceHeader& h) {
  const std::string other = fs::path(first.slice.path).filename().string();
  if (h.rows != first.rows || h.columns != first.columns)
    return makeError(ErrorCode::kSizeMismatch, h.slice.path,
                     ": tag Rows x Columns (0028,0010/0011): ", h.columns, "x", h.rows,
                     " differs from ", first.columns, "x", first.rows, " in ", other);
  if (h.bitsAllocated != first.bitsAllocated || h.pixelRepresentation != first.pixelRepresentation)
    return makeError(ErrorCode::kSizeMismatch, h.slice.path,
                     ": tag BitsAllocated/PixelRepresentation (0028,0100/0103): ", h.bitsAllocated,
                     "/", h.pixelRepresentation, " differs from ", first.bitsAllocated, "/",
                     first.pixelRepresentation, " in ", other);
  for (int i = 0; i < 6; ++i)
    if (std::fabs(h.orientation[i] - first.orientation[i]) > 1e-4)
      return makeError(ErrorCode::kUnsupported, h.slice.path,
                       ": tag ImageOrientationPatient (0020,0037) differs from ", other);
  for (int i = 0; i < 2; ++i)
    if (std::fabs(h.pixelSpacing[i] - first.pixelSpacing[i]) > 1e-4 * first.pixelSpacing[i])
      return makeError(ErrorCode::kSizeMismatch, h.slice.path,
                       ": tag PixelSpacing (0028,0030): ", h.pixelSpacing[0], "\\",
                       h.pixelSpacing[1], " differs from ", first.pixelSpacing[0], "\\",
                       first.pixelSpacing[1], " in ", other);
  return Status::ok();
}

// Spacing from the sorted slice positions; errors or notes when the gaps are not uniform.
Status sliceSpacing(DicomSeries& s, const std::string& dir) {
  const size_t n = s.slices.size();
  if (n == 1) {
    s.notes.push_back("a single slice: z spacing 1");
    s.sliceSpacing = 1;
    return Status::ok();
  }
  const double mean = (s.slices.back().along - s.slices.front().along) / static_cast<double>(n - 1);
  double worst = 0;
  size_t worstAt = 0;
  for (size_t i = 0; i + 1 < n; ++i) {
    const double gap = s.slices[i + 1].along - s.slices[i].along;
    if (gap <= 1e-6 * std::max(1.0, std::fabs(mean)))
      return makeError(ErrorCode::kCorrupt, dir, ": tag ImagePositionPatient (0020,0032): ",
                       fs::path(s.slices[i].path).filename().string(), " and ",
                       fs::path(s.slices[i + 1].path).filename().string(),
                       " lie at the same slice position");
    if (std::fabs(gap - mean) > worst) {
      worst = std::fabs(gap - mean);
      worstAt = i;
    }
  }
  const double relative = worst / mean;
  if (relative > 1e-2) {
    const double gap = s.slices[worstAt + 1].along - s.slices[worstAt].along;
    return makeError(
        ErrorCode::kUnsupported, dir, ": tag ImagePositionPatient (0020,0032): slice gaps ",
        "are not uniform: ", gap, " mm between ",
        fs::path(s.slices[worstAt].path).filename().string(), " and ",
        fs::path(s.slices[worstAt + 1].path).filename().string(), ", mean ", mean, " mm");
  }
  if (relative > 1e-3)
    s.notes.push_back(cat("slice gaps vary by up to ", worst, " mm around the mean ", mean,
                          " mm used as z spacing"));
  s.sliceSpacing = mean;
  return Status::ok();
}

std::string orderNote(const std::vector<DicomSlice>& slices) {
  bool ascending = true, descending = true;
  for (size_t i = 0; i + 1 < slices.size(); ++i) {
    if (slices[i + 1].instance <= slices[i].instance) ascending = false;
    if (slices[i + 1].instance >= slices[i].instance) descending = false;
  }
  std::string note = "slices sorted by position along the slice normal (increasing)";
  if (slices.size() < 2) return note;
  if (descending) return note + "; z order is the reverse of InstanceNumber order";
  if (!ascending) return note + "; z order differs from InstanceNumber order";
  return note + "; same as InstanceNumber order";
}

}  // namespace

Result<DicomSeries> scanDicomSeries(const std::string& dir) {
  std::vector<std::string> files;
  size_t skipped = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (!entry.is_regular_file(ec)) continue;
    if (looksLikeDicom(entry.path()))
      files.push_back(entry.path().string());
    else
      ++skipped;
  }
  if (ec) return makeError(ErrorCode::kIo, dir, ": cannot list the folder (", ec.message(), ")");
  if (files.empty())
    return makeError(ErrorCode::kCorrupt, dir,
                     ": no DICOM files (.dcm or DICM magic) in the folder");
  std::sort(files.begin(), files.end(),
            [](const std::string& a, const std::string& b) { return naturalLess(a, b); });

  VOXLINK_RETURN_IF_ERROR(checkGdcmSurvives(files));
  std::vector<SliceHeader> headers;
  std::map<std::string, size_t> seriesCount;
  for (const std::string& f : files) {
    VOXLINK_ASSIGN_OR_RETURN(SliceHeader h, readSliceHeader(f));
    ++seriesCount[h.series];
    headers.push_back(std::move(h));
  }
  if (seriesCount.size() > 1)
    return makeError(ErrorCode::kUnsupported, dir,
                     ": tag SeriesInstanceUID (0020,000E): the folder holds ", seriesCount.size(),
                     " series; point at a folder holding one");

  DicomSeries s;
  const SliceHeader& first = headers.front();
  for (const SliceHeader& h : headers) VOXLINK_RETURN_IF_ERROR(checkSameGeometry(first, h));
  VOXLINK_ASSIGN_OR_RETURN(s.storedType, storedType(first));
  s.rows = first.rows;
  s.columns = first.columns;
  s.bitsStored = first.bitsStored;
  s.rowDirection = {first.orientation[0], first.orientation[1], first.orientation[2]};
  s.columnDirection = {first.orientation[3], first.orientation[4], first.orientation[5]};
  s.normal = cross(s.rowDirection, s.columnDirection);
  const double normalLength = length(s.normal);
  if (normalLength < 0.5)
    return makeError(
        ErrorCode::kCorrupt, first.slice.path,
        ": tag ImageOrientationPatient (0020,0037): row and column directions are parallel");
  for (double& c : s.normal) c /= normalLength;
  s.rowSpacing = first.pixelSpacing[0];
  s.columnSpacing = first.pixelSpacing[1];
  if (!(s.rowSpacing > 0) || !(s.columnSpacing > 0))
    return makeError(ErrorCode::kCorrupt, first.slice.path,
                     ": tag PixelSpacing (0028,0030): ", s.rowSpacing, "\\", s.columnSpacing,
                     ", expected positive numbers");
  if (first.photometric == "MONOCHROME1")
    s.notes.push_back(
        "PhotometricInterpretation MONOCHROME1: values kept as stored (high = dark on display)");
  if (skipped > 0) s.notes.push_back(cat(skipped, " non-DICOM files in the folder skipped"));

  for (SliceHeader& h : headers) {
    h.slice.along = dot(h.slice.position, s.normal);
    s.slices.push_back(h.slice);
  }
  std::stable_sort(s.slices.begin(), s.slices.end(),
                   [](const DicomSlice& a, const DicomSlice& b) { return a.along < b.along; });
  VOXLINK_RETURN_IF_ERROR(sliceSpacing(s, dir));
  s.notes.push_back(orderNote(s.slices));
  return s;
}

}  // namespace voxlink::convert
