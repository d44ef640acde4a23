// SPDX-License-Identifier: BSD-3-Clause
// A scene's volume object: a .vxl as it is, or a dense source (any file `voxlink convert`
// reads) classified with the object's threshold or transfer function by the converter itself,
// so that a scene holding only that volume has the voxels `voxlink convert` gives.
#pragma once

#include <functional>

#include "base/error.h"
#include "format/voxlink_file.h"
#include "scene/scene_description.h"

namespace voxlink::scene {

// A dense source is converted with the scene grid's brick size and axis into a temporary file
// (removed again once opened); `progress` as convert's.
Result<format::VoxLinkFile> openSceneVolume(
    const SceneObject& object, const SceneGrid& grid,
    const std::function<void(double fraction, const char* stage)>& progress = {});

}  // namespace voxlink::scene
