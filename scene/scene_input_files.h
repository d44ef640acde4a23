// SPDX-License-Identifier: BSD-3-Clause
// Every file building a scene reads, so that `scene build -o` can refuse to write over one: the
// scene file, each object's file, an OBJ's material libraries, a volume's transfer function,
// and a dense volume's own files (a detached header's data files, a DICOM folder's slices).
#pragma once

#include <string>
#include <vector>

#include "scene/scene_description.h"

namespace voxlink::scene {

// Files that cannot be opened are left out: the build itself reports them.
std::vector<std::string> sceneInputFiles(const SceneDescription& scene);

}  // namespace voxlink::scene
