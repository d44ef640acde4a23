// SPDX-License-Identifier: BSD-3-Clause
// The validator's checks of a version 2.1 file's fragment lists (FROF, FRAG, TRID, TRIS): every
// list 1..kMaxFragmentsPerVoxel long, every plane and triangle finite with a material in the
// table, reserved bits zero. format/validator.cpp calls it for scenes.
#pragma once

#include "base/error.h"
#include "format/voxlink_file.h"

namespace voxlink::format {

// Ok for a file without fragment lists.
Status checkFragmentLists(const VoxLinkFile& f);

}  // namespace voxlink::format
