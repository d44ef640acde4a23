// SPDX-License-Identifier: BSD-3-Clause
// The scene JSON (scene/scene_description.h), parsed in memory as `voxlink scene build` reads
// it; an accepted scene's transforms are applied and its material names looked up, the way
// scene assembly uses them. Files the scene names are not loaded (the mesh and particles
// targets cover those readers).
#include <string>

#include "fuzz/fuzz_targets.h"
#include "scene/scene_description.h"

namespace voxlink::fuzz {

Status fuzzScene(Input input) {
  const std::string text(input.begin(), input.end());
  auto scene = scene::parseSceneDescription(text, "fuzz.scene.json");
  if (!scene) return scene.status();
  volatile double sum = 0;
  for (const scene::SceneObject& object : scene->objects) {
    const auto p = object.transform.apply(object.center);
    sum = sum + p[0] + object.transform.uniformScale() + object.radius * object.radiusScale;
    if (object.material) sum = sum + (scene->findMaterial(*object.material) != nullptr);
  }
  return Status::ok();
}

}  // namespace voxlink::fuzz
