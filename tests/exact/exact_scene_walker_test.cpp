// SPDX-License-Identifier: BSD-3-Clause
// The exact walker against analytic answers: sphere hits and normals to 1e-9, a unit quad, every
// surface along a ray in front-to-back order, early stop and the [tMin, tMax] window.
#include "exact/exact_scene_walker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "scene/scene_description.h"
#include "tests/exact/exact_fixtures.h"
#include "tests/support/test_util.h"

namespace voxlink::exact {
namespace {

using render::Ray;
using render::SceneEvent;
using testing::addQuad;
using testing::addSphere;
using testing::makeWalker;
using testing::material;

std::vector<SceneEvent> allEvents(const ExactSceneWalker& w, const Ray& ray, double tMin = 0,
                                  double tMax = HUGE_VAL) {
  std::vector<SceneEvent> events;
  w.walk(ray, tMin, tMax, [&](const SceneEvent& e) {
    events.push_back(e);
    return true;
  });
  return events;
}

TEST(ExactSceneWalker, SphereHitsAndNormalsAreExact) {
  scene::PlacedScene s;
  s.materials = {material({1, 0, 0})};
  const glm::dvec3 c(0.25, -0.5, 0.125);
  const double r = 0.75;  // centre and radius exact in float
  addSphere(s, {float(c.x), float(c.y), float(c.z)}, float(r), 0);
  const auto w = makeWalker(std::move(s));
  ASSERT_TRUE(w);
  // Rays from many directions at many offsets from the centre.
  for (int i = 0; i < 50; ++i) {
    const double theta = 0.37 * i, phi = 0.11 * i;
    const glm::dvec3 d = glm::normalize(glm::dvec3(std::cos(theta) * std::cos(phi),
                                                   std::sin(theta) * std::cos(phi), std::sin(phi)));
    glm::dvec3 side = glm::normalize(glm::cross(d, glm::dvec3(0.3, 0.4, 0.5)));
    const double b = 0.7 * r * (i % 10) / 9.0;  // distance of the ray from the centre
    const Ray ray{c - 5.0 * d + b * side, d};
    const double half = std::sqrt(r * r - b * b);
    const auto events = allEvents(*w, ray);
    ASSERT_EQ(events.size(), 2u) << "ray " << i;
    EXPECT_NEAR(events[0].t, 5.0 - half, 1e-9) << "ray " << i;
    EXPECT_NEAR(events[1].t, 5.0 + half, 1e-9) << "ray " << i;
    for (const SceneEvent& e : events) {
      const glm::dvec3 expected = (ray.origin + e.t * d - c) / r;
      EXPECT_NEAR(glm::length(e.normal - expected), 0.0, 1e-9) << "ray " << i;
      EXPECT_EQ(e.kind, SceneEvent::Kind::kSurface);
      EXPECT_EQ(e.material, 0u);
    }
    EXPECT_LT(glm::dot(events[0].normal, d), 0);  // outward: against the ray on entry
    EXPECT_GT(glm::dot(events[1].normal, d), 0);
  }
  // A ray that passes beside the sphere meets nothing.
  EXPECT_TRUE(
      allEvents(*w, Ray{c + glm::dvec3(0, 0, 0.76) - glm::dvec3(5, 0, 0), {1, 0, 0}}).empty());
}

TEST(ExactSceneWalker, UnitQuadHitDistanceNormalAndEdges) {
  scene::PlacedScene s;
  s.materials = {material({0, 1, 0})};
  addQuad(s, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0);  // normal +z
  const auto w = makeWalker(std::move(s));
  ASSERT_TRUE(w);
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.1, -0.2, -1.0));
  for (const glm::dvec2 target : {glm::dvec2(0.25, 0.6), glm::dvec2(0.5, 0.5) /* diagonal */,
                                  glm::dvec2(0.9, 0.05), glm::dvec2(1e-3, 1e-3)}) {
    const glm::dvec3 p(target, 0.0);
    const auto events = allEvents(*w, Ray{p - 3.0 * d, d});
    ASSERT_EQ(events.size(), 1u) << "one surface, even where the ray meets the shared edge";
    EXPECT_NEAR(events[0].t, 3.0, 1e-12);
    EXPECT_EQ(events[0].normal, glm::dvec3(0, 0, 1));
  }
  EXPECT_TRUE(allEvents(*w, Ray{{1.5, 0.5, 1.0}, {0, 0, -1}}).empty());
  EXPECT_TRUE(allEvents(*w, Ray{{0.5, 0.5, 1.0}, {0, 0, 1}}).empty());  // pointing away
}

// Three quads at z = 0, 1, 2 and a sphere between the first two, met from above: every surface,
// nearest first, each with its own material.
class Stack : public ::testing::Test {
 protected:
  void SetUp() override {
    scene::PlacedScene s;
    for (int m = 0; m < 4; ++m) s.materials.push_back(material({0.2f * m, 0, 0}, 0.5f));
    for (int q = 0; q < 3; ++q)
      addQuad(s, {-2, -2, float(q)}, {2, -2, float(q)}, {2, 2, float(q)}, {-2, 2, float(q)},
              uint16_t(q));
    addSphere(s, {0, 0, 0.5f}, 0.25f, 3);
    walker = makeWalker(std::move(s));
    ASSERT_TRUE(walker);
  }
  std::unique_ptr<ExactSceneWalker> walker;
  const Ray down{{0.0, 0.0, 5.0}, {0.0, 0.0, -1.0}};
};

TEST_F(Stack, EveryHitFrontToBack) {
  const auto events = allEvents(*walker, down);
  ASSERT_EQ(events.size(), 5u);
  const double t[] = {3.0, 4.0, 4.25, 4.75, 5.0};
  const uint32_t m[] = {2, 1, 3, 3, 0};
  for (size_t i = 0; i < events.size(); ++i) {
    EXPECT_NEAR(events[i].t, t[i], 1e-12) << i;
    EXPECT_EQ(events[i].material, m[i]) << i;
  }
}

TEST_F(Stack, StopsWhenVisitSaysSoAndKeepsToTheWindow) {
  int calls = 0;
  walker->walk(down, 0, HUGE_VAL, [&](const SceneEvent&) { return ++calls < 2; });
  EXPECT_EQ(calls, 2);
  const auto inside = allEvents(*walker, down, 3.5, 4.5);
  ASSERT_EQ(inside.size(), 2u);
  EXPECT_NEAR(inside[0].t, 4.0, 1e-12);
  EXPECT_NEAR(inside[1].t, 4.25, 1e-12);
  // Starting just past a surface (as a secondary ray does) does not meet it again.
  const auto after = allEvents(*walker, down, 3.0 + walker->surfaceOffset(), HUGE_VAL);
  ASSERT_EQ(after.size(), 4u);
  EXPECT_NEAR(after[0].t, 4.0, 1e-12);
}

TEST(ExactSceneWalker, RefusesAVolumeScene) {
  const auto dir = std::filesystem::temp_directory_path() / "voxlink_exact_volume_scene";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "with-volume.scene.json").string();
  std::ofstream(path) << R"({"objects": [{"type": "volume", "file": "foot.vxl"},
      {"type": "sphere", "center": [0, 0, 0], "radius": 1}]})";
  auto description = scene::readSceneDescription(path);
  ASSERT_TRUE(description) << description.message();
  auto walker = ExactSceneWalker::open(*description);
  ASSERT_FALSE(walker);
  EXPECT_NE(walker.message().find("not a volume"), std::string::npos) << walker.message();
  EXPECT_NE(walker.message().find("with-volume.scene.json"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace voxlink::exact
