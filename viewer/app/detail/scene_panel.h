// SPDX-License-Identifier: BSD-3-Clause
// The ImGui panel of a scene file with moving meshes: play/pause and the animation time, the
// moving objects (select one to drag; release a dragged one back to its animation), and
// where the grid stopped the last drag.
#pragma once

#include <optional>

#include "viewer/app/scene_session.h"

namespace voxlink::viewer {

// Returns true when the image must be drawn again; an error (a mesh that cannot move) goes to
// `message`.
bool drawScenePanel(SceneSession& session, std::optional<size_t>& selected, std::string& message);

}  // namespace voxlink::viewer
