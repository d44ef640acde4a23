// SPDX-License-Identifier: BSD-3-Clause
// The ray-traced scene mode's optics in float64 (EffectsTracer) against cases worked out by
// hand: a perfect mirror, the lateral shift of a ray through a glass slab (Snell's law), total
// internal reflection, a half-reflective half-refractive surface whose two rays must add up to
// one unsplit ray, no NaN or value above 1 where every input lies in [0, 1], and termination
// between parallel mirrors and with the camera inside glass.
#include "render/effects_tracer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/detail/light_transport.h"
#include "tests/viewer/analytic_scene.h"

namespace voxlink::render {

namespace {

using testing::analyticMaterial;
using testing::AnalyticPlane;
using testing::AnalyticScene;
using testing::AnalyticSphere;

const tf::TransferFunction kNoVolume{};

RenderSettings unlit(Effects effects) {
  RenderSettings s;
  s.width = s.height = 8;
  s.shading.enabled = false;  // a surface shows its colour (zero here) plus its emission
  s.effects = effects;
  return s;
}

Effects allEffects() {
  Effects e;
  e.reflect = e.refract = true;
  return e;
}

std::array<double, 4> trace(const AnalyticScene& scene, const glm::dvec3& origin,
                            const glm::dvec3& direction, const RenderSettings& s) {
  const EffectsTracer tracer(scene, kNoVolume);
  const Camera camera = Camera::lookAt(glm::dvec3(0, -10, 0), glm::dvec3(0.0), {0, 0, 1}, 30);
  return tracer.traceRay(Ray{origin, glm::normalize(direction)}, camera, s);
}

const glm::dvec3 kBlack(0.0);

TEST(EffectsTracer, PerfectMirrorShowsWhatItFaces) {
  AnalyticScene scene;
  scene.materialTable = {analyticMaterial(kBlack, 0, /*reflectivity=*/1),
                         analyticMaterial(kBlack, /*emission=*/0.7)};
  scene.planes = {{{0, 0, 0}, {0, 0, 1}, 0}, {{5, 0, 0}, {-1, 0, 0}, 1}};
  const auto c = trace(scene, {0, 0, 1}, {1, 0, -1}, unlit(allEffects()));
  EXPECT_NEAR(c[0], 0.7, 1e-7);
  EXPECT_NEAR(c[3], 1.0, 1e-12);  // nothing reached the background
  ASSERT_EQ(scene.walked.size(), 2u);
  const glm::dvec3 r = scene.walked[1].direction;
  EXPECT_NEAR(r.x, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(r.z, std::sqrt(0.5), 1e-12);
  // Without the reflect effect the mirror's share is drawn as its (black) diffuse colour.
  Effects none;
  scene.walked.clear();
  EXPECT_NEAR(trace(scene, {0, 0, 1}, {1, 0, -1}, unlit(none))[0], 0.0, 1e-12);
}

TEST(EffectsTracer, GlassSlabShiftsTheRayBySnellsLaw) {
  const double h = 0.8, ior = 1.5, theta = 40.0 * M_PI / 180.0;
  AnalyticScene scene;
  scene.materialTable = {analyticMaterial(kBlack, 0, 0, /*transmission=*/1, ior)};
  scene.planes = {{{0, 0, 0}, {0, 0, 1}, 0}, {{0, 0, -h}, {0, 0, -1}, 0}};
  const glm::dvec3 d(std::sin(theta), 0, -std::cos(theta));
  const glm::dvec3 o(0, 0, 1);
  const auto c = trace(scene, o, d, unlit(allEffects()));
  ASSERT_EQ(scene.walked.size(), 3u);  // outside, inside the glass, out again
  const double thetaT = std::asin(std::sin(theta) / ior);
  const Ray inside = scene.walked[1], out = scene.walked[2];
  EXPECT_NEAR(inside.direction.x, std::sin(thetaT), 1e-12);
  EXPECT_NEAR(glm::length(out.direction - d), 0.0, 1e-12);  // leaves parallel to the entry
  // Perpendicular distance between the incoming and the outgoing line.
  const glm::dvec3 between = out.origin - o;
  const double shift = glm::length(between - glm::dot(between, d) * d);
  EXPECT_NEAR(shift, h * std::sin(theta - thetaT) / std::cos(thetaT), 1e-6);
  EXPECT_NEAR(c[3], 0.0, 1e-12);  // all of it went on to the background
}

TEST(EffectsTracer, TotalInternalReflectionMirrorsTheRefractedShare) {
  // Camera inside a glass slab (z in [-1, 0]) looking up at 60 degrees from the normal; the
  // critical angle of index 1.5 is 41.8 degrees. The slab's floor is an emitter.
  AnalyticScene scene;
  scene.materialTable = {analyticMaterial(kBlack, 0, 0, 1, 1.5),
                         analyticMaterial(kBlack, /*emission=*/0.6)};
  scene.planes = {{{0, 0, 0}, {0, 0, 1}, 0}, {{0, 0, -1}, {0, 0, 1}, 1}};
  const double theta = 60.0 * M_PI / 180.0;
  const auto c =
      trace(scene, {0, 0, -0.5}, {std::sin(theta), 0, std::cos(theta)}, unlit(allEffects()));
  ASSERT_EQ(scene.walked.size(), 2u);
  EXPECT_NEAR(scene.walked[1].direction.z, -std::cos(theta), 1e-12);
  EXPECT_NEAR(c[0], 0.6, 1e-7);
  EXPECT_FALSE(refractDirection({std::sin(theta), 0, std::cos(theta)}, {0, 0, 1}, 1.5, false));
  EXPECT_TRUE(refractDirection({std::sin(0.7), 0, std::cos(0.7)}, {0, 0, 1}, 1.5, false));
}

TEST(EffectsTracer, SplitRaysAddUpToOneUnsplitRay) {
  // A surface at z = 0 that reflects half and refracts half (index 1: no bending); emitters above
  // and below. Equal emitters: the pixel equals one unsplit ray's (a full mirror). Unequal: the
  // pixel is the shares' weighted sum. Opacity 0.6: 0.4 passes straight on.
  for (const double below : {0.5, 0.2}) {
    AnalyticScene scene;
    scene.materialTable = {analyticMaterial(kBlack, 0, 0.5, 0.5, 1.0),
                           analyticMaterial(kBlack, 0.5), analyticMaterial(kBlack, below),
                           analyticMaterial(kBlack, 0, 1.0)};
    scene.planes = {
        {{0, 0, 0}, {0, 0, 1}, 0}, {{0, 0, 3}, {0, 0, -1}, 1}, {{0, 0, -3}, {0, 0, 1}, 2}};
    const glm::dvec3 o(0, 0, 1), d(1, 0, -1);
    const double split = trace(scene, o, d, unlit(allEffects()))[0];
    EXPECT_NEAR(split, 0.5 * 0.5 + 0.5 * below, 1e-7);
    scene.planes[0].material = 3;
    const double mirror = trace(scene, o, d, unlit(allEffects()))[0];
    if (below == 0.5) {
      EXPECT_NEAR(split, mirror, 1e-7);
    }
    scene.materialTable[0].opacity = 0.6f;
    scene.planes[0].material = 0;
    EXPECT_NEAR(trace(scene, o, d, unlit(allEffects()))[0],
                0.6 * (0.5 * 0.5 + 0.5 * below) + 0.4 * below, 1e-6);
  }
}

TEST(EffectsTracer, NoPixelIsNaNOrAboveOneWhenInputsLieInZeroOne) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 6; ++trial) {
    AnalyticScene scene;
    for (int m = 0; m < 6; ++m) {
      const double r = u(rng), t = (1 - r) * u(rng);
      scene.materialTable.push_back(
          analyticMaterial({u(rng), u(rng), u(rng)}, 0, r, t, 1 + u(rng), /*opacity=*/u(rng)));
    }
    for (int s = 0; s < 5; ++s)
      scene.spheres.push_back(AnalyticSphere{
          {4 * u(rng) - 2, 4 * u(rng) - 2, 4 * u(rng) - 2}, 0.3 + u(rng), uint32_t(s % 6)});
    scene.planes.push_back({{0, 0, -3}, {0, 0, 1}, 5});
    scene.box = Box{glm::dvec3(-4.0), glm::dvec3(4.0)};
    RenderSettings s;
    s.width = s.height = 24;
    s.shading.specular = 0;  // ambient + diffuse <= 1
    s.effects = allEffects();
    s.effects.shadows = true;
    s.effects.maxBounces = 6;
    s.background = {1, 1, 1};
    const Camera camera = Camera::framing(scene.box, CameraSpec{});
    const Image image = EffectsTracer(scene, kNoVolume).render(camera, s);
    for (float v : image.rgba) {
      ASSERT_TRUE(std::isfinite(v));
      ASSERT_GE(v, 0.0f);
      ASSERT_LE(v, 1.0f + 1e-5f);
    }
  }
}

TEST(EffectsTracer, RaysTerminateBetweenParallelMirrors) {
  AnalyticScene scene;
  scene.materialTable = {analyticMaterial(kBlack, 0, 1.0)};
  scene.planes = {{{0, 0, 1}, {0, 0, -1}, 0}, {{0, 0, -1}, {0, 0, 1}, 0}};
  for (int bounces : {0, 4, 16}) {
    Effects e = allEffects();
    e.maxBounces = bounces;
    scene.walked.clear();
    const auto c = trace(scene, {0, 0, 0}, {0.3, 0, 1}, unlit(e));
    EXPECT_EQ(scene.walked.size(), size_t(bounces) + 1);
    EXPECT_TRUE(std::isfinite(c[0]));
    // A grazing ray, parallel to both mirrors, meets neither.
    scene.walked.clear();
    EXPECT_NEAR(trace(scene, {0, 0, 0}, {1, 0, 0}, unlit(e))[3], 0.0, 1e-12);
    EXPECT_EQ(scene.walked.size(), 1u);
  }
}

TEST(EffectsTracer, CameraInsideAGlassSphere) {
  AnalyticScene scene;
  scene.materialTable = {analyticMaterial(kBlack, 0, 0.0, 1.0, 1.5), analyticMaterial(kBlack, 0.8)};
  scene.spheres = {{{0, 0, 0}, 1.0, 0}};
  scene.planes = {{{0, 5, 0}, {0, -1, 0}, 1}};
  scene.box = Box{glm::dvec3(-6.0), glm::dvec3(6.0)};
  // Straight ahead through the surface at normal incidence: no bending, onto the emitter.
  const auto c = trace(scene, {0, 0, 0}, {0, 1, 0}, unlit(allEffects()));
  EXPECT_NEAR(c[0], 0.8, 1e-6);
  RenderSettings s = unlit(allEffects());
  s.width = s.height = 16;
  const Camera inside = Camera::lookAt({0, 0, 0}, {0, 1, 0}, {0, 0, 1}, 90);
  const Image image = EffectsTracer(scene, kNoVolume).render(inside, s);
  for (float v : image.rgba) ASSERT_TRUE(std::isfinite(v) && v >= 0 && v <= 1.0f + 1e-6f);
}

}  // namespace
}  // namespace voxlink::render
