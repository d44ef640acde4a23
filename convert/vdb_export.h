// SPDX-License-Identifier: BSD-3-Clause
// A VoxLink file as an OpenVDB file for Blender, Houdini and vdb_view: a FloatGrid "values" of
// the stored voxels in source units and a Vec3SGrid "gradient" of their decoded unit gradients,
// both with the index-to-world transform of the file's spacing and origin and the file's META
// as metadata. The work is done in the OpenVDB plugin; exportVdb() loads it, so executables
// do not link OpenVDB.
#pragma once

#include <string>

#include "base/error.h"
#include "base/progress.h"
#include "format/voxlink_file.h"

namespace voxlink::convert {

struct VdbExportSummary {
  uint64_t voxels = 0;  // active voxels of each grid
  uint64_t bytes = 0;   // the written file
};

// Validates the file first; writes a temporary file beside `path`, renamed when complete.
// `progress` (may be empty) hears the validation, every 32nd of the voxels set in the grids,
// and the writing.
Result<VdbExportSummary> exportVdb(const format::VoxLinkFile& file, const std::string& path,
                                   const base::ProgressCallback& progress = {});
// The plugin's side (links OpenVDB); the file must be valid.
Result<VdbExportSummary> exportVdbDirect(const format::VoxLinkFile& file, const std::string& path,
                                         const base::ProgressCallback& progress = {});

}  // namespace voxlink::convert
