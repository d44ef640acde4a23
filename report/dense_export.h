// SPDX-License-Identifier: BSD-3-Clause
// The classified volume dense again: every stored voxel's value in the source's type, removed
// voxels set to a fill value, written as an NRRD file (attached header, raw little-endian data),
// or for a path ending in .nhdr as a detached header and NAME.raw beside it (raw + header: any
// tool that takes dims and a type reads the .raw). The NRRD reader of sources/ and other tools
// read both. Streams one brick layer (n slices) at a time, to a temporary file renamed into
// place when complete.
#pragma once

#include <string>
#include <string_view>

#include "base/error.h"
#include "base/progress.h"
#include "format/voxlink_file.h"

namespace voxlink::report {

using format::VoxLinkFile;

struct DenseExportSummary {
  uint64_t bytes = 0;         // the whole output file
  uint64_t keptVoxels = 0;    // voxels holding a stored value
  uint64_t filledVoxels = 0;  // voxels holding the fill
};

// kInvalidArgument (naming `where` and the value as typed) when `fill` is not finite, does not
// fit `type`, or is not a whole number for an integer type: one rule for every dense export,
// so the command line and Python give the same volume or the same error.
// `option` names the setting as the caller's user typed it.
Status checkFill(ScalarType type, double fill, const std::string& where,
                 std::string_view option = "--fill");

// Fails as checkFill does (naming `path`); kUnsupported for a scene (version 2) file, whose
// VALU is not indexed by voxel. `progress` (may be empty) hears the fraction of brick layers
// written after each one.
Result<DenseExportSummary> exportDenseNrrd(const VoxLinkFile& file, const std::string& path,
                                           double fill, const ProgressCallback& progress = {});

}  // namespace voxlink::report
