// SPDX-License-Identifier: BSD-3-Clause
// What a scene file says about how to look at it, as render/'s structs: its camera (the
// default view, as `voxlink render` takes it from a built scene's META) and its point lights.
// The exact tracer renders straight from the scene file, with no .vxl to read them from.
#pragma once

#include <vector>

#include "render/camera.h"
#include "render/effects.h"
#include "scene/scene_description.h"

namespace voxlink::exact {

// The scene's "camera" object over CameraSpec's defaults (azimuth, elevation, distance, fov, up).
render::CameraSpec sceneCameraSpec(const scene::SceneDescription& scene);
// Point lights, radiance = colour * intensity.
std::vector<render::Light> sceneLights(const scene::SceneDescription& scene);

}  // namespace voxlink::exact
