// SPDX-License-Identifier: BSD-3-Clause
#include "tests/exact/exact_fixtures.h"

#include <gtest/gtest.h>

namespace voxlink::exact::testing {

format::MaterialRecord material(std::array<float, 3> color, float opacity, float reflectivity,
                                float transmission, float ior) {
  format::MaterialRecord m{};
  for (int c = 0; c < 3; ++c) m.color[c] = color[c];
  m.opacity = opacity;
  m.reflectivity = reflectivity;
  m.transmission = transmission;
  m.refractiveIndex = ior;
  return m;
}

void addQuad(scene::PlacedScene& s, const std::array<float, 3>& a, const std::array<float, 3>& b,
             const std::array<float, 3>& c, const std::array<float, 3>& d, uint16_t material) {
  const uint32_t base = uint32_t(s.mesh.vertexCount());
  for (const auto& p : {a, b, c, d})
    s.mesh.positions.insert(s.mesh.positions.end(), p.begin(), p.end());
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) s.mesh.triangles.push_back(base + i);
  s.mesh.triangleMaterials.push_back(material);
  s.mesh.triangleMaterials.push_back(material);
}

void addSphere(scene::PlacedScene& s, const std::array<float, 3>& center, float radius,
               uint16_t material) {
  geometry::Sphere sphere;
  sphere.center = center;
  sphere.radius = radius;
  sphere.material = material;
  s.spheres.push_back(sphere);
}

std::unique_ptr<ExactSceneWalker> makeWalker(scene::PlacedScene s, double extent) {
  const render::Box box{glm::dvec3(-extent), glm::dvec3(extent)};
  auto walker = ExactSceneWalker::create(std::move(s), box);
  EXPECT_TRUE(walker.isOk()) << (walker ? "" : walker.message());
  return walker ? std::move(*walker) : nullptr;
}

}  // namespace voxlink::exact::testing
