// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/dicom_series.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "base/limits.h"
#include "sources/readers/detail/dicom_pixel_encoding.h"
#include "sources/readers/detail/dicom_probe.h"
#include "sources/readers/detail/file_list.h"
#include "sources/readers/detail/gdcm_guard.h"

namespace voxlink::sources {
namespace {

namespace fs = std::filesystem;

std::string fileName(const std::string& path) { return fs::path(path).filename().string(); }

struct FoundFiles {
  std::vector<std::string> dicom;  // natural sort
  uint64_t other = 0;
};

// `path` itself when it is a file; else every DICOM file below it (DICOMDIR, an index of the
// same files, is counted with the other files: the walk finds what it references).
Result<FoundFiles> findFiles(const std::string& path) {
  FoundFiles found;
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) {
    found.dicom.push_back(path);
    return found;
  }
  fs::recursive_directory_iterator it(path, fs::directory_options::skip_permission_denied, ec);
  for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    if (looksLikeDicom(it->path()))
      found.dicom.push_back(it->path().string());
    else
      ++found.other;
    if (found.dicom.size() > limits::kMaxListedFiles)
      return makeError(ErrorCode::kTooLarge, path, ": more than ", limits::kMaxListedFiles,
                       " DICOM files below the folder");
  }
  if (ec) return makeError(ErrorCode::kIo, path, ": cannot list the folder (", ec.message(), ")");
  if (found.dicom.empty())
    return makeError(ErrorCode::kCorrupt, path,
                     ": no DICOM files (.dcm or DICM magic) in the folder or below it");
  std::sort(found.dicom.begin(), found.dicom.end(),
            [](const std::string& a, const std::string& b) { return naturalLess(a, b); });
  return found;
}

struct Group {
  std::string uid;
  std::vector<DicomFileHeader> files;
};

struct Scan {
  std::vector<Group> groups;
  uint64_t otherFiles = 0, nonImages = 0;
};

// Reads every header (after the child process survived them all) and groups the images by
// SeriesInstanceUID in the order of their first file.
Result<Scan> scanHeaders(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(FoundFiles found, findFiles(path));
  VOXLINK_RETURN_IF_ERROR(checkGdcmSurvives(found.dicom));
  Scan scan;
  scan.otherFiles = found.other;
  std::map<std::string, size_t> index;
  for (const std::string& f : found.dicom) {
    VOXLINK_ASSIGN_OR_RETURN(DicomFileHeader h, readDicomFileHeader(f));
    if (!h.image) {
      ++scan.nonImages;
      continue;
    }
    auto [at, added] = index.emplace(h.series, scan.groups.size());
    if (added) scan.groups.push_back({h.series, {}});
    scan.groups[at->second].files.push_back(std::move(h));
  }
  if (scan.groups.empty())
    return makeError(ErrorCode::kUnsupported, path, ": none of the ", found.dicom.size(),
                     " DICOM files is an image (no PixelData, Rows, Columns)");
  return scan;
}

Result<ScalarType> storedType(const DicomFileHeader& h) {
  const bool s = h.pixelRepresentation == 1;
  switch (h.bitsAllocated) {
    case 8:
      return s ? ScalarType::kI8 : ScalarType::kU8;
    case 16:
      return s ? ScalarType::kI16 : ScalarType::kU16;
    case 32:
      return s ? ScalarType::kI32 : ScalarType::kU32;
    default:
      return makeError(ErrorCode::kUnsupported, h.path,
                       ": tag BitsAllocated (0028,0100): ", h.bitsAllocated,
                       " (8, 16 or 32 are supported)");
  }
}

Status checkSameGeometry(const DicomFileHeader& first, const DicomFileHeader& h) {
  const std::string other = fileName(first.path);
  if (h.rows != first.rows || h.columns != first.columns)
    return makeError(ErrorCode::kSizeMismatch, h.path,
                     ": tag Rows x Columns (0028,0010/0011): ", h.columns, "x", h.rows,
                     " differs from ", first.columns, "x", first.rows, " in ", other);
  if (h.bitsAllocated != first.bitsAllocated || h.pixelRepresentation != first.pixelRepresentation)
    return makeError(ErrorCode::kSizeMismatch, h.path,
                     ": tag BitsAllocated/PixelRepresentation (0028,0100/0103): ", h.bitsAllocated,
                     "/", h.pixelRepresentation, " differs from ", first.bitsAllocated, "/",
                     first.pixelRepresentation, " in ", other);
  for (int i = 0; i < 6; ++i)
    if (std::fabs(h.orientation[i] - first.orientation[i]) > 1e-4)
      return makeError(ErrorCode::kUnsupported, h.path,
                       ": tag ImageOrientationPatient (0020,0037) differs from ", other,
                       " (mixed orientations)");
  for (int i = 0; i < 2; ++i)
    if (std::fabs(h.pixelSpacing[i] - first.pixelSpacing[i]) > 1e-4 * first.pixelSpacing[i])
      return makeError(ErrorCode::kSizeMismatch, h.path,
                       ": tag PixelSpacing (0028,0030): ", h.pixelSpacing[0], "\\",
                       h.pixelSpacing[1], " differs from ", first.pixelSpacing[0], "\\",
                       first.pixelSpacing[1], " in ", other);
  if (h.hasPosition != first.hasPosition)
    return makeError(ErrorCode::kCorrupt, (h.hasPosition ? first : h).path,
                     ": tag ImagePositionPatient (0020,0032) missing, but ",
                     fileName((h.hasPosition ? h : first).path), " of the same series has it");
  return Status::ok();
}

// The z spacing a series without positions gets, and where it came from.
std::pair<double, std::string> nominalSpacing(const DicomFileHeader& h) {
  if (h.spacingBetweenSlices > 0) return {h.spacingBetweenSlices, "SpacingBetweenSlices"};
  if (h.sliceThickness > 0) return {h.sliceThickness, "SliceThickness"};
  return {1.0, "neither SpacingBetweenSlices nor SliceThickness given"};
}

// Spacing from the sorted slice positions; errors or notes when the gaps are not uniform or
// the slices are not stacked straight along the normal (gantry tilt).
Status sliceSpacing(DicomSeries& s, const DicomFileHeader& first, const std::string& dir) {
  const size_t n = s.slices.size();
  if (n == 1) {
    const auto [spacing, from] = nominalSpacing(first);
    s.notes.push_back(cat("a single slice: z spacing ", spacing, " (", from, ")"));
    s.sliceSpacing = spacing;
    return Status::ok();
  }
  const double mean = (s.slices.back().along - s.slices.front().along) / static_cast<double>(n - 1);
  double worst = 0;
  size_t worstAt = 0;
  for (size_t i = 0; i + 1 < n; ++i) {
    const double gap = s.slices[i + 1].along - s.slices[i].along;
    if (gap <= 1e-6 * std::max(1.0, std::fabs(mean)))
      return makeError(ErrorCode::kCorrupt, dir,
                       ": tag ImagePositionPatient (0020,0032): ", sliceName(s.slices[i]), " and ",
                       sliceName(s.slices[i + 1]), " lie at the same slice position");
    if (std::fabs(gap - mean) > worst) {
      worst = std::fabs(gap - mean);
      worstAt = i;
    }
  }
  const double relative = worst / mean;
  if (relative > 1e-2) {
    const double gap = s.slices[worstAt + 1].along - s.slices[worstAt].along;
    return makeError(ErrorCode::kUnsupported, dir,
                     ": tag ImagePositionPatient (0020,0032): slice gaps are not uniform: ", gap,
                     " mm between ", sliceName(s.slices[worstAt]), " and ",
                     sliceName(s.slices[worstAt + 1]), ", mean ", mean, " mm");
  }
  if (relative > 1e-3)
    s.notes.push_back(cat("slice gaps vary by up to ", worst, " mm around the mean ", mean,
                          " mm used as z spacing"));
  // Slices must stack along the normal: a shift across the plane is a tilted (sheared) grid.
  const Vec3 p0 = s.slices.front().position;
  const double pixel = std::min(s.rowSpacing, s.columnSpacing);
  for (const DicomSlice& slice : s.slices) {
    const double d = slice.along - s.slices.front().along;
    Vec3 shift;
    for (int a = 0; a < 3; ++a) shift[a] = slice.position[a] - p0[a] - d * s.normal[a];
    const double off = length(shift);
    if (off > 5e-2 * pixel) {  // DS text rounding stays far below this
      const double degrees = std::atan2(off, d) * 180.0 / M_PI;
      return makeError(ErrorCode::kUnsupported, dir,
                       ": tag ImagePositionPatient (0020,0032): ", sliceName(slice), " lies ", off,
                       " mm across the slice plane from ", sliceName(s.slices.front()), " at ", d,
                       " mm along the normal (gantry tilt of ", degrees,
                       " degrees; the grid is sheared, resample it first)");
    }
  }
  s.sliceSpacing = mean;
  return Status::ok();
}

std::string orderNote(const std::vector<DicomSlice>& slices) {
  bool ascending = true, descending = true;
  for (size_t i = 0; i + 1 < slices.size(); ++i) {
    if (slices[i + 1].instance <= slices[i].instance) ascending = false;
    if (slices[i + 1].instance >= slices[i].instance) descending = false;
  }
  const bool frames = slices.front().fileFrames > 1;
  const char* order = frames ? "frame order" : "InstanceNumber order";
  std::string note = "slices sorted by position along the slice normal (increasing)";
  if (slices.size() < 2) return note;
  if (descending) return cat(note, "; z order is the reverse of ", order);
  if (!ascending) return cat(note, "; z order differs from ", order);
  return cat(note, "; same as ", order);
}

// The volume of one series: geometry checked, slices ordered, spacing and origin found.
Result<DicomSeries> buildSeries(const std::vector<DicomFileHeader>& files, const std::string& dir) {
  DicomSeries s;
  const DicomFileHeader& first = files.front();
  for (const DicomFileHeader& h : files) VOXLINK_RETURN_IF_ERROR(checkSameGeometry(first, h));
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
        ErrorCode::kCorrupt, first.path,
        ": tag ImageOrientationPatient (0020,0037): row and column directions are parallel");
  for (double& c : s.normal) c /= normalLength;
  s.rowSpacing = first.pixelSpacing[0];
  s.columnSpacing = first.pixelSpacing[1];
  if (!(s.rowSpacing > 0) || !(s.columnSpacing > 0) || !std::isfinite(s.rowSpacing) ||
      !std::isfinite(s.columnSpacing))
    return makeError(ErrorCode::kCorrupt, first.path,
                     ": tag PixelSpacing (0028,0030): ", s.rowSpacing, "\\", s.columnSpacing,
                     ", expected positive numbers");
  if (!first.hasPixelSpacing) s.notes.push_back("PixelSpacing (0028,0030) missing: x, y spacing 1");
  if (!first.hasOrientation)
    s.notes.push_back("ImageOrientationPatient (0020,0037) missing: rows along +x, columns +y");
  if (first.photometric == "MONOCHROME1")
    s.notes.push_back(
        "PhotometricInterpretation MONOCHROME1: values kept as stored (high = dark on display)");
  if (first.frames.front().extendSign)
    s.notes.push_back(cat("PixelRepresentation 1 in ", transferSyntaxName(first.transferSyntax),
                          ": decoded samples sign-extended from BitsStored ", first.bitsStored,
                          " bits (the codestream may hold them unsigned; DICOM's header decides)"));
  if (std::any_of(files.begin(), files.end(),
                  [](const DicomFileHeader& h) { return h.modalityLut; }))
    s.notes.push_back(
        "Modality LUT Sequence (0028,3000) not applied: values are the stored pixel values");
  for (const DicomFileHeader& h : files) {
    if (!h.rescaleField.empty()) s.rescaleField = h.rescaleField;
    for (DicomSlice slice : h.frames) {
      slice.along = dot(slice.position, s.normal);
      s.slices.push_back(slice);
    }
  }
  if (s.slices.size() > limits::kMaxAxis)
    return makeError(ErrorCode::kTooLarge, dir, ": ", s.slices.size(), " slices, more than ",
                     limits::kMaxAxis);
  if (first.hasPosition) {
    std::stable_sort(s.slices.begin(), s.slices.end(),
                     [](const DicomSlice& a, const DicomSlice& b) { return a.along < b.along; });
    VOXLINK_RETURN_IF_ERROR(sliceSpacing(s, first, dir));
    s.origin = s.slices.front().position;
    s.notes.push_back(orderNote(s.slices));
    if (first.frames.size() > 1)
      s.notes.push_back(cat("frame positions from ", first.positionField));
    return s;
  }
  // No positions: the order the files give, the nominal spacing, origin 0, said out loud.
  std::stable_sort(s.slices.begin(), s.slices.end(), [](const DicomSlice& a, const DicomSlice& b) {
    return a.instance < b.instance;
  });
  const auto [spacing, from] = nominalSpacing(first);
  s.sliceSpacing = spacing;
  s.notes.push_back(cat(s.slices.size() == 1 ? "a single image" : "images",
                        " without ImagePositionPatient (0020,0032): origin 0, ",
                        s.slices.size() == 1 ? "" : "slices in InstanceNumber/frame order, ",
                        "z spacing ", spacing, " (", from, ")"));
  return s;
}

std::string seriesLine(size_t index, const Group& g) {
  const DicomFileHeader& h = g.files.front();
  uint64_t frames = 0;
  for (const DicomFileHeader& f : g.files) frames += f.frames.size();
  return cat(index + 1, " ", g.uid.empty() ? "(no UID)" : g.uid, " (", h.modality,
             h.description.empty() ? "" : " '" + h.description + "'", ", ", g.files.size(),
             " files, ", frames, " images)");
}

Result<size_t> chooseSeries(const Scan& scan, const std::string& path, const std::string& choice) {
  std::string all;
  for (size_t i = 0; i < scan.groups.size(); ++i)
    all += (i ? "; " : "") + seriesLine(i, scan.groups[i]);
  if (choice.empty()) {
    if (scan.groups.size() == 1) return size_t{0};
    return makeError(ErrorCode::kUnsupported, path,
                     ": tag SeriesInstanceUID (0020,000E): the folder holds ", scan.groups.size(),
                     " series; pick one with --series UID or INDEX: ", all);
  }
  for (size_t i = 0; i < scan.groups.size(); ++i)
    if (scan.groups[i].uid == choice) return i;
  if (!choice.empty() && choice.size() < 8 &&
      std::all_of(choice.begin(), choice.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    const size_t n = std::stoul(choice);
    if (n >= 1 && n <= scan.groups.size()) return n - 1;
  }
  return makeError(ErrorCode::kInvalidArgument, path, ": --series ", choice,
                   ": no such series UID or index; the folder holds: ", all);
}

}  // namespace

Result<DicomFolderListing> listDicomSeries(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(Scan scan, scanHeaders(path));
  DicomFolderListing listing;
  listing.otherFiles = scan.otherFiles;
  listing.nonImages = scan.nonImages;
  for (const Group& g : scan.groups) {
    DicomSeriesSummary s;
    s.uid = g.uid;
    s.modality = g.files.front().modality;
    s.description = g.files.front().description;
    s.files = g.files.size();
    for (const DicomFileHeader& h : g.files) {
      s.frames += h.frames.size();
      std::error_code ec;
      const uint64_t size = fs::file_size(h.path, ec);
      if (!ec) s.bytes += size;
    }
    auto series = buildSeries(g.files, path);
    if (series) {
      s.dims = {series->columns, series->rows, static_cast<uint32_t>(series->slices.size())};
      s.spacing = {series->columnSpacing, series->rowSpacing, series->sliceSpacing};
    } else {
      s.problem = series.message();
    }
    listing.series.push_back(std::move(s));
  }
  return listing;
}

Result<DicomSeries> scanDicomSeries(const std::string& path, const std::string& choice) {
  VOXLINK_ASSIGN_OR_RETURN(Scan scan, scanHeaders(path));
  VOXLINK_ASSIGN_OR_RETURN(size_t chosen, chooseSeries(scan, path, choice));
  VOXLINK_ASSIGN_OR_RETURN(DicomSeries s, buildSeries(scan.groups[chosen].files, path));
  if (scan.groups.size() > 1)
    s.notes.push_back(cat("series ", chosen + 1, " of ", scan.groups.size(),
                          " in the folder: ", scan.groups[chosen].uid));
  if (scan.otherFiles > 0)
    s.notes.push_back(cat(scan.otherFiles, " non-DICOM files in the folder skipped"));
  if (scan.nonImages > 0)
    s.notes.push_back(
        cat(scan.nonImages, " DICOM files without an image (reports, RT structures, ...) skipped"));
  return s;
}

}  // namespace voxlink::sources
