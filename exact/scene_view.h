// What a scene file says about how to look at it, as the viewer's structs: its camera (the
// default view, as `voxlink render` takes it from a built scene's META) and its point lights.
// The exact tracer renders straight from the scene file, with no .vxl to read them from.
#pragma once

#include <vector>

#include "scene/scene_description.h"
#include "viewer/core/camera.h"
#include "viewer/core/effects.h"

namespace voxlink::exact {

// The scene's "camera" object over CameraSpec's defaults (azimuth, elevation, distance, fov, up).
viewer::CameraSpec sceneCameraSpec(const scene::SceneDescription& scene);
// Point lights, radiance = colour * intensity.
std::vector<viewer::Light> sceneLights(const scene::SceneDescription& scene);

}  // namespace voxlink::exact
