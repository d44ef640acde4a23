// SPDX-License-Identifier: BSD-3-Clause
// GSLIB / GEO-EAS grids as SGeMS and the GSLIB programs write them: a title line, the number
// of variables, one name per line, then one row per node (x fastest, then y, then z) with a
// value per variable. Plain text, or the single member of a .zip archive (libzip).
//
// Grid size: SGeMS writes "nx ny nz" as the title; other titles need --dims (OpenOptions
// dims). When both exist they must agree, and the row count must equal nx * ny * nz.
// Variable: options.variable names the column (default: the first, with a note).
// Point sets (columns named X and Y) are not grids and are refused: krige them instead.
// Values are served as f64, streamed: each read parses the next slices (rewind to restart).
#pragma once

#include <memory>
#include <string>

#include "sources/volume_source.h"

namespace voxlink::sources {

Result<std::unique_ptr<VolumeSource>> openGslib(const std::string& path,
                                                const OpenOptions& options);

// True for names ending in .sgems, .gslib, .geoeas, .gslib.zip or .sgems.zip (any case).
bool looksLikeGslib(const std::string& path);

}  // namespace voxlink::sources
