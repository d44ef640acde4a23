// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/metaimage_reader.h"

#include <filesystem>

#include "sources/readers/detail/data_pieces.h"
#include "sources/readers/detail/metaimage_header.h"
#include "sources/readers/reader_common.h"

namespace voxlink::sources {

Result<std::unique_ptr<VolumeSource>> openMetaImage(const std::string& path,
                                                    const OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(MetaImageHeader h, parseMetaImageHeader(path));
  const std::array<uint64_t, 3> dims{h.dimSize[0], h.dimSize[1], h.dimSize[2]};
  VOXLINK_RETURN_IF_ERROR(checkDims(dims, path, "DimSize"));

  VolumeInfo info;
  info.path = path;
  info.format = "metaimage";
  info.type = h.type;
  for (int a = 0; a < 3; ++a) info.dims[a] = static_cast<uint32_t>(dims[a]);
  if (h.ndims == 4) info.notes.push_back("4-D MetaImage with a last size of 1: read as 3-D");
  if (h.spacing.empty()) {
    info.notes.push_back("no ElementSpacing: spacing 1 1 1");
  } else {
    for (int a = 0; a < 3; ++a) info.spacing[a] = h.spacing[a];
    if (h.spacingFromElementSize)
      info.notes.push_back("no ElementSpacing: spacing taken from ElementSize");
    VOXLINK_RETURN_IF_ERROR(checkSpacing(
        info.spacing, path, h.spacingFromElementSize ? "ElementSize" : "ElementSpacing"));
  }
  if (h.offset) info.origin = *h.offset;
  if (h.axes) {
    const AxesSummary s = summarizeAxes(*h.axes, "TransformMatrix axes");
    if (!s.note.empty()) info.notes.push_back(s.note);
  }
  VOXLINK_RETURN_IF_ERROR(applyOpenOptions(info, options));

  PieceLayout layout;
  layout.encoding = h.compressed ? PieceEncoding::kDeflate : PieceEncoding::kRaw;
  layout.endian = h.endian;
  layout.label = cat(path, ": ElementDataFile");
  DataPiece base;
  base.startOffset = h.headerSize > 0 ? static_cast<uint64_t>(h.headerSize) : 0;
  base.dataAtEnd = h.headerSize == -1;
  if (h.local) {
    base.path = path;
    base.startOffset += h.localOffset;
    base.slices = info.dims[2];
    layout.pieces.push_back(base);
  } else {
    VOXLINK_RETURN_IF_ERROR(
        addDataFilePieces(base, h.dataFiles, info.dims[2], path, "ElementDataFile", layout));
  }
  // CompressedDataSize is advisory here: the stream is decoded to its end. Say so when it
  // disagrees with the file (VTK's frogtissue.mhd states 260020 for a 262087-byte .zraw).
  if (h.compressed && h.compressedSize && layout.pieces.size() == 1) {
    std::error_code ec;
    const uint64_t size = std::filesystem::file_size(layout.pieces[0].path, ec);
    const uint64_t start = layout.pieces[0].startOffset;
    if (!ec && size >= start && size - start != *h.compressedSize)
      info.notes.push_back(cat("CompressedDataSize ", *h.compressedSize, " disagrees with the ",
                               size - start,
                               " compressed bytes in the file; the stream was read to its end"));
  }
  return openDataPieces(std::move(info), std::move(layout));
}

}  // namespace voxlink::sources
