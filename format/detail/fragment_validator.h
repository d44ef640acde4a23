// SPDX-License-Identifier: BSD-3-Clause
// The validator's checks of a version 2.1 file's fragment lists (FROF, FRAG, TRID, TRIS): every
// list 1..kMaxFragmentsPerVoxel long, every plane and triangle finite with a material in the
// table, reserved bits zero. format/validator.cpp calls it for scenes.
#pragma once

#include <string>

#include "base/error.h"
#include "format/voxlink_file.h"

namespace voxlink::format {

// The header's version 2.1 counts (checkHeader calls it for version 2): surfaceMode known,
// triangleCount and fragmentCount zero in mode 0, else 1..kMaxFragmentsPerVoxel per surface
// voxel. `where` prefixes messages.
Status checkFragmentCounts(const FileHeader& h, const std::string& where);

// Ok for a file without fragment lists.
Status checkFragmentLists(const VoxLinkFile& f);

}  // namespace voxlink::format
