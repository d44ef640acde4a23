// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/nifti_reader.h"

#include <nifti2_io.h>
#include <zlib.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <optional>

#include "base/stderr_capture.h"
#include "sources/readers/detail/axes.h"
#include "sources/readers/detail/data_pieces.h"
#include "sources/readers/detail/reader_registry.h"
#include "sources/readers/detail/rescale.h"
#include "sources/readers/reader_common.h"

namespace voxlink::sources {
namespace {

// nifti_image::byteorder values; nifti2_io.h defines MSB_FIRST only for its own .c file.
constexpr int kMsbFirst = 2;

// pixdim[1..3] as stored: libnifti replaces 0, negative and NaN values by 1 without saying so.
// NIfTI-1 keeps float pixdim[8] at byte 76, NIfTI-2 double pixdim[8] at byte 104; sizeof_hdr
// (348 or 540, in either byte order) tells which. zlib reads plain and gzip files alike.
std::optional<std::array<double, 3>> storedPixdim(const std::string& path) {
  gzFile f = gzopen(path.c_str(), "rb");
  if (!f) return std::nullopt;
  uint8_t h[168] = {};
  const int got = gzread(f, h, sizeof h);
  gzclose(f);
  if (got < 108) return std::nullopt;
  uint32_t size = 0;
  std::memcpy(&size, h, 4);
  const bool swap = size == __builtin_bswap32(348u) || size == __builtin_bswap32(540u);
  if (swap) size = __builtin_bswap32(size);
  std::array<double, 3> out{};
  for (int a = 0; a < 3; ++a) {
    if (size == 348) {
      uint32_t bits;
      std::memcpy(&bits, h + 76 + 4 * (a + 1), 4);
      if (swap) bits = __builtin_bswap32(bits);
      float v;
      std::memcpy(&v, &bits, 4);
      out[a] = v;
    } else if (size == 540 && got >= 168) {
      uint64_t bits;
      std::memcpy(&bits, h + 104 + 8 * (a + 1), 8);
      if (swap) bits = __builtin_bswap64(bits);
      std::memcpy(&out[a], &bits, 8);
    } else {
      return std::nullopt;
    }
  }
  return out;
}

struct NiftiDeleter {
  void operator()(nifti_image* nim) const { nifti_image_free(nim); }
};

std::optional<ScalarType> niftiType(int datatype) {
  switch (datatype) {
    case DT_UINT8:
      return ScalarType::kU8;
    case DT_INT8:
      return ScalarType::kI8;
    case DT_UINT16:
      return ScalarType::kU16;
    case DT_INT16:
      return ScalarType::kI16;
    case DT_UINT32:
      return ScalarType::kU32;
    case DT_INT32:
      return ScalarType::kI32;
    case DT_FLOAT32:
      return ScalarType::kF32;
    case DT_FLOAT64:
      return ScalarType::kF64;
    default:
      return std::nullopt;
  }
}

std::pair<double, double> typeRange(ScalarType type) {
  return dispatchScalar(type, [](auto tag) {
    using T = decltype(tag);
    return std::pair<double, double>(static_cast<double>(std::numeric_limits<T>::lowest()),
                                     static_cast<double>(std::numeric_limits<T>::max()));
  });
}

// Origin (and a note on the axes) from the sform when set, else the qform, else none.
void applyTransform(const nifti_image& nim, VolumeInfo& info) {
  const nifti_dmat44* m = nullptr;
  std::string source;
  if (nim.sform_code > 0) {
    m = &nim.sto_xyz;
    source = cat("sform (code ", nim.sform_code, ", ", nifti_xform_string(nim.sform_code), ")");
  } else if (nim.qform_code > 0) {
    m = &nim.qto_xyz;
    source = cat("qform (code ", nim.qform_code, ", ", nifti_xform_string(nim.qform_code), ")");
  }
  if (!m) {
    info.notes.push_back("no sform or qform: origin 0 0 0");
    return;
  }
  info.origin = {m->m[0][3], m->m[1][3], m->m[2][3]};
  std::array<Vec3, 3> axes{};
  for (int a = 0; a < 3; ++a) axes[a] = {m->m[0][a], m->m[1][a], m->m[2][a]};
  info.notes.push_back(cat("origin from the ", source, "; spacing from pixdim"));
  const AxesSummary s = summarizeAxes(axes, cat(source, " axes"));
  if (!s.note.empty()) info.notes.push_back(s.note);
}

}  // namespace

Result<std::unique_ptr<VolumeSource>> openNifti(const std::string& path,
                                                const OpenOptions& options) {
  static std::once_flag quiet;
  std::call_once(quiet, [] { nifti_set_debug_level(0); });  // errors come back as ours
  std::unique_ptr<nifti_image, NiftiDeleter> nim;
  std::string reason;
  {
    // libnifti prints its complaints to stderr; they become part of our one line instead.
    base::StderrCapture capture;
    nim.reset(nifti_image_read(path.c_str(), 0));
    reason = capture.firstLine();
  }
  if (!nim)
    return makeError(ErrorCode::kCorrupt, path,
                     ": not a readable NIfTI-1/NIfTI-2 header (libnifti2 refused it",
                     reason.empty() ? "" : ": ", reason, ")");
  if (nim->nifti_type == NIFTI_FTYPE_ASCII)
    return makeError(ErrorCode::kUnsupported, path, ": NIfTI ASCII files are not supported");

  const int64_t ndim = nim->dim[0];
  if (ndim < 3)
    return makeError(ErrorCode::kUnsupported, path, ": header field 'dim[0]': ", ndim,
                     " (a volume needs 3)");
  for (int d = 4; d <= ndim && d < 8; ++d)
    if (nim->dim[d] > 1)
      return makeError(ErrorCode::kUnsupported, path, ": header field 'dim[", d,
                       "]': ", nim->dim[d], " (only a single 3-D volume is supported)");
  const std::array<uint64_t, 3> dims{static_cast<uint64_t>(std::max<int64_t>(nim->dim[1], 0)),
                                     static_cast<uint64_t>(std::max<int64_t>(nim->dim[2], 0)),
                                     static_cast<uint64_t>(std::max<int64_t>(nim->dim[3], 0))};
  VOXLINK_RETURN_IF_ERROR(checkDims(dims, path, "dim"));
  const auto type = niftiType(nim->datatype);
  if (!type)
    return makeError(ErrorCode::kUnsupported, path, ": header field 'datatype': ", nim->datatype,
                     " (", nifti_datatype_string(nim->datatype),
                     "; scalar uint8 .. float64 are supported)");

  VolumeInfo info;
  info.path = path;
  info.format = "nifti";
  info.type = *type;
  for (int a = 0; a < 3; ++a) {
    info.dims[a] = static_cast<uint32_t>(dims[a]);
    info.spacing[a] = std::fabs(nim->pixdim[a + 1]);
  }
  // libnifti turned 0, negative or NaN pixdim into 1: an error for NaN/inf (unless --spacing
  // replaces it), a note for 0 (written by some tools for "unknown").
  if (const auto stored = storedPixdim(path)) {
    for (int a = 0; a < 3; ++a) {
      const double v = (*stored)[a];
      if (!std::isfinite(v) && !options.spacing)
        return makeError(ErrorCode::kCorrupt, path, ": header field 'pixdim[", a + 1, "]': ", v,
                         " is not a spacing; give --spacing X,Y,Z");
      if (v == 0 && !options.spacing)
        info.notes.push_back(cat("header field 'pixdim[", a + 1,
                                 "]' is 0 (unknown): spacing 1 used; give --spacing to set it"));
    }
  }
  VOXLINK_RETURN_IF_ERROR(checkSpacing(info.spacing, path, "pixdim"));
  if (nim->xyz_units == NIFTI_UNITS_METER || nim->xyz_units == NIFTI_UNITS_MICRON)
    info.notes.push_back(
        cat("spacing and origin are in ", nifti_units_string(nim->xyz_units), " (xyzt_units)"));
  if (nim->nifti_type == NIFTI_FTYPE_ANALYZE)
    info.notes.push_back("Analyze 7.5 header: no orientation");
  applyTransform(*nim, info);

  // NIfTI: scl_slope 0 means "no scaling"; 1 and 0 change nothing.
  const double slope = nim->scl_slope, intercept = nim->scl_inter;
  const bool scaled = slope != 0 && std::isfinite(slope) && std::isfinite(intercept) &&
                      !(slope == 1 && intercept == 0);
  const auto [lo, hi] = typeRange(*type);
  const ScalarType served = scaled ? rescaledType(*type, lo, hi, slope, intercept) : *type;
  {
    // --dims/--type are checked against what is served (the rescaled type).
    VolumeInfo check = info;
    check.type = served;
    VOXLINK_RETURN_IF_ERROR(applyOpenOptions(check, options));
    info.spacing = check.spacing;
    info.notes = check.notes;
  }

  PieceLayout layout;
  layout.label = cat(path, ": image data");
  layout.endian = nim->byteorder == kMsbFirst ? Endian::kBig : Endian::kLittle;
  DataPiece piece;
  piece.path = nim->iname ? nim->iname : path;
  piece.slices = info.dims[2];
  if (lowerExtension(piece.path).ends_with(".gz")) {
    layout.encoding = PieceEncoding::kDeflate;
    piece.byteSkip = static_cast<uint64_t>(nim->iname_offset);  // counted in decoded bytes
  } else {
    piece.startOffset = static_cast<uint64_t>(nim->iname_offset);
  }
  layout.pieces.push_back(piece);
  nim.reset();
  VOXLINK_ASSIGN_OR_RETURN(std::unique_ptr<VolumeSource> source,
                           openDataPieces(std::move(info), std::move(layout)));
  if (!scaled) return source;
  return rescaleSource(std::move(source), slope, intercept, served, "scl_slope/scl_inter");
}

}  // namespace voxlink::sources
