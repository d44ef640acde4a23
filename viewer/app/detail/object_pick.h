// SPDX-License-Identifier: BSD-3-Clause
// Which moving object is under a pixel: the nearest of their current boxes that the camera's
// primary ray through the pixel enters. Boxes, not the voxels: a click beside a mesh but
// inside its box picks it. Free of GL so tests can check it.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "render/camera.h"

namespace voxlink::viewer {

// Distance along `ray` to where it enters `box` (0 when it starts inside), or none.
std::optional<double> rayEntersBox(const render::Ray& ray, const render::Box& box);

// The index in `boxes` of the nearest box hit by the primary ray through pixel (px, py) of a
// width x height image, or none (also for a pixel outside the image).
std::optional<size_t> pickBox(const render::Camera& camera, double px, double py, uint32_t width,
                              uint32_t height, const std::vector<render::Box>& boxes);

}  // namespace voxlink::viewer
