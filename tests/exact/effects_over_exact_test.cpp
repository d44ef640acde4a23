// SPDX-License-Identifier: BSD-3-Clause
// EffectsTracer over the exact walker on scenes whose pixels are known: a mirror shows a diffuse
// quad exactly as a direct ray from the mirrored direction sees it, and semi-transparent
// surfaces composite front to back.
#include <gtest/gtest.h>

#include <cmath>

#include "render/effects_tracer.h"
#include "tests/exact/exact_fixtures.h"

namespace voxlink::exact {
namespace {

using render::Ray;
using testing::addQuad;
using testing::makeWalker;
using testing::material;

render::RenderSettings settingsWith(bool reflect, bool shadows) {
  render::RenderSettings s;
  s.effects.reflect = reflect;
  s.effects.shadows = shadows;
  s.background = {0.1, 0.2, 0.3};
  // One directional light, so shading depends on the normal and the view direction only; it
  // lights the wall (x = 2, facing -x) from the front, so diffuse, highlight and shadow rays count.
  const glm::dvec3 l = glm::normalize(glm::dvec3(-0.6, -0.3, 0.74));
  s.lights = {render::Light{{l.x, l.y, l.z}, {1, 1, 1}, /*directional=*/true}};
  return s;
}

const render::Camera kCamera = render::Camera::lookAt({0, -5, 1}, {0, 0, 0}, {0, 0, 1}, 30);

// A mirror floor z = 0 and a diffuse wall x = 2 facing -x. The ray that reaches wall point P
// with direction dr after bouncing off the floor must see what a direct ray along dr sees.
TEST(EffectsOverExact, MirrorShowsWhatADirectRaySees) {
  scene::PlacedScene s;
  s.materials = {material({1, 1, 1}, 1, /*reflectivity=*/1), material({0.8f, 0.4f, 0.2f})};
  s.materials[1].specular = 0.5f;
  s.materials[1].shininess = 20;
  addQuad(s, {-4, -4, 0}, {4, -4, 0}, {4, 4, 0}, {-4, 4, 0}, 0);  // floor, normal +z
  addQuad(s, {2, -4, 0}, {2, -4, 4}, {2, 4, 4}, {2, 4, 0}, 1);    // wall, normal -x
  const auto w = makeWalker(std::move(s));
  ASSERT_TRUE(w);
  const render::EffectsTracer tracer(*w, tf::TransferFunction{});
  for (bool shadows : {false, true}) {
    const auto settings = settingsWith(/*reflect=*/true, shadows);
    for (const glm::dvec3 p : {glm::dvec3(2, 0.5, 1.5), glm::dvec3(2, -1, 0.7)}) {
      const glm::dvec3 dr = glm::normalize(glm::dvec3(1, 0.2, 0.3));  // towards the wall, upwards
      const glm::dvec3 floorHit = p - (p.z / dr.z) * dr;
      const glm::dvec3 down(dr.x, dr.y, -dr.z);
      const auto direct = tracer.traceRay(Ray{p - 0.5 * dr, dr}, kCamera, settings);
      const auto mirrored = tracer.traceRay(Ray{floorHit - 1.0 * down, down}, kCamera, settings);
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(mirrored[c], direct[c], 1e-12) << c;
      EXPECT_GT(direct[0], 0.8 * 0.3 + 0.05);  // more than ambient: the wall is lit
      EXPECT_EQ(direct[3], 1.0);
    }
    // Without reflection the mirror is shaded as a white diffuse floor instead.
    const auto plain = settingsWith(/*reflect=*/false, shadows);
    const auto floorOnly =
        tracer.traceRay(Ray{{0, 0, 1}, glm::normalize(glm::dvec3(1, 0, -1))}, kCamera, plain);
    EXPECT_NEAR(floorOnly[0], floorOnly[1], 1e-12);  // white: grey levels, not the wall's colour
  }
}

// Two half-transparent unlit quads in front of the background: c = a1 c1 + (1 - a1) a2 c2 +
// (1 - a1)(1 - a2) bg, alpha = 1 - (1 - a1)(1 - a2).
TEST(EffectsOverExact, SemiTransparentSurfacesComposite) {
  scene::PlacedScene s;
  s.materials = {material({1, 0, 0}, 0.5f), material({0, 1, 0}, 0.25f)};
  addQuad(s, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}, 0);
  addQuad(s, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, 1);
  const auto w = makeWalker(std::move(s));
  ASSERT_TRUE(w);
  const render::EffectsTracer tracer(*w, tf::TransferFunction{});
  auto settings = settingsWith(false, false);
  settings.shading.enabled = false;
  const auto c = tracer.traceRay(Ray{{0.3, 0.2, 3}, {0, 0, -1}}, kCamera, settings);
  EXPECT_NEAR(c[0], 0.5 + 0.5 * 0.75 * 0.1, 1e-12);
  EXPECT_NEAR(c[1], 0.5 * 0.25 + 0.5 * 0.75 * 0.2, 1e-12);
  EXPECT_NEAR(c[2], 0.5 * 0.75 * 0.3, 1e-12);
  EXPECT_NEAR(c[3], 1 - 0.5 * 0.75, 1e-12);
}

}  // namespace
}  // namespace voxlink::exact
