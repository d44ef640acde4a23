// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/nrrd_reader.h"

#include <cmath>
#include <filesystem>

#include "sources/readers/detail/axes.h"
#include "sources/readers/detail/data_pieces.h"
#include "sources/readers/detail/nrrd_header.h"
#include "sources/readers/reader_common.h"

namespace voxlink::sources {
namespace {

// Spacing and origin from 'spacings' or 'space directions' (axes `first`..`first+2`).
Status applyGeometry(const NrrdHeader& h, int first, const std::string& path, VolumeInfo& info) {
  if (!h.directions.empty()) {
    std::array<Vec3, 3> axes{};
    for (int a = 0; a < 3; ++a) {
      if (!h.directions[first + a])
        return makeError(ErrorCode::kCorrupt, path, ": header field 'space directions': axis ",
                         first + a, " is 'none' but is a spatial axis");
      axes[a] = *h.directions[first + a];
    }
    if (first == 1 && h.directions[0])
      return makeError(ErrorCode::kCorrupt, path,
                       ": header field 'space directions': the first "
                       "axis of a 4-D volume must be 'none'");
    const AxesSummary s = summarizeAxes(axes, "space directions");
    info.spacing = s.lengths;
    if (!s.note.empty()) info.notes.push_back(s.note);
    VOXLINK_RETURN_IF_ERROR(checkSpacing(info.spacing, path, "space directions"));
  } else if (!h.spacings.empty()) {
    for (int a = 0; a < 3; ++a) info.spacing[a] = h.spacings[first + a];
    VOXLINK_RETURN_IF_ERROR(checkSpacing(info.spacing, path, "spacings"));
  } else {
    info.notes.push_back("no 'spacings' or 'space directions': spacing 1 1 1");
  }
  if (h.origin) info.origin = *h.origin;
  return Status::ok();
}

}  // namespace

Result<std::unique_ptr<VolumeSource>> openNrrd(const std::string& path,
                                               const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(NrrdHeader h, parseNrrdHeader(path));
  const int first = h.dimension == 4 ? 1 : 0;
  const std::array<uint64_t, 3> dims{h.sizes[first], h.sizes[first + 1], h.sizes[first + 2]};
  VOXLINK_RETURN_IF_ERROR(checkDims(dims, path, "sizes"));

  VolumeInfo info;
  info.path = path;
  info.format = "nrrd";
  info.type = h.type;
  for (int a = 0; a < 3; ++a) info.dims[a] = static_cast<uint32_t>(dims[a]);
  if (first == 1) info.notes.push_back("4-D NRRD with a first axis of size 1: read as 3-D");
  VOXLINK_RETURN_IF_ERROR(applyGeometry(h, first, path, info));
  VOXLINK_RETURN_IF_ERROR(applyOpenOptions(info, options));

  PieceLayout layout;
  layout.encoding = h.encoding;
  layout.endian = h.endian.value_or(Endian::kLittle);
  layout.label = cat(path, h.attached ? ": data" : ": data file");
  DataPiece base;
  base.lineSkip = h.lineSkip;
  base.byteSkip = h.byteSkip > 0 ? static_cast<uint64_t>(h.byteSkip) : 0;
  base.dataAtEnd = h.byteSkip == -1;
  if (h.attached) {
    base.path = path;
    base.startOffset = h.dataOffset;
    base.slices = info.dims[2];
    layout.pieces.push_back(base);
  } else {
    const uint64_t files = h.dataFiles.size();
    // A <subdim> of 2 (or 3 for 4-D) means one z slice per file.
    const int sliceSubdim = h.dimension - 1;
    const bool subdimFits = h.dataFileSubdim == 0 || h.dataFileSubdim == h.dimension ||
                            (h.dataFileSubdim == sliceSubdim && files == info.dims[2]);
    if (!subdimFits) return unevenDataFiles(path, "data file", files, info.dims[2]);
    VOXLINK_RETURN_IF_ERROR(
        addDataFilePieces(base, h.dataFiles, info.dims[2], path, "data file", layout));
    if (files > 1) info.notes.push_back(cat("data in ", files, " files"));
  }
  return openDataPieces(std::move(info), std::move(layout));
}

}  // namespace voxlink::sources
