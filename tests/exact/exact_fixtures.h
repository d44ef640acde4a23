// SPDX-License-Identifier: BSD-3-Clause
// Hand-built scenes for the exact walker's tests: quads (two triangles each) and spheres with
// their own materials.
#pragma once

#include <array>
#include <memory>

#include "exact/exact_scene_walker.h"
#include "scene/scene_geometry.h"

namespace voxlink::exact::testing {

format::MaterialRecord material(std::array<float, 3> color, float opacity = 1,
                                float reflectivity = 0, float transmission = 0, float ior = 1);

// The quad a, b, c, d (counter-clockwise seen from where its normal points) as triangles
// (a, b, c) and (a, c, d).
void addQuad(scene::PlacedScene& s, const std::array<float, 3>& a, const std::array<float, 3>& b,
             const std::array<float, 3>& c, const std::array<float, 3>& d, uint16_t material);
void addSphere(scene::PlacedScene& s, const std::array<float, 3>& center, float radius,
               uint16_t material);

// The walker over `s`, clipped to the cube [-extent, extent]^3; fails the test on error.
std::unique_ptr<ExactSceneWalker> makeWalker(scene::PlacedScene s, double extent = 10);

}  // namespace voxlink::exact::testing
