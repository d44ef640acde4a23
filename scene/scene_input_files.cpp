// SPDX-License-Identifier: BSD-3-Clause
#include "scene/scene_input_files.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sources/volume_source.h"

namespace voxlink::scene {
namespace {

namespace fs = std::filesystem;

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// The MTL files an OBJ names (`mtllib a.mtl b.mtl`, beside the OBJ) and the OBJ-stem.mtl the
// mesh loader falls back to.
std::vector<std::string> materialLibraries(const std::string& objPath) {
  std::vector<std::string> files;
  const fs::path folder = fs::path(objPath).parent_path();
  std::ifstream in(objPath);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("mtllib", 0) != 0) continue;
    std::istringstream words(line.substr(6));
    std::string name;
    while (words >> name) files.push_back((folder / name).string());
  }
  files.push_back(fs::path(objPath).replace_extension(".mtl").string());
  return files;
}

}  // namespace

std::vector<std::string> sceneInputFiles(const SceneDescription& scene) {
  std::vector<std::string> files = {scene.path};
  for (const SceneObject& object : scene.objects) {
    if (object.path.empty()) continue;
    files.push_back(object.path);
    if (!object.tfPath.empty()) files.push_back(object.tfPath);
    if (object.kind == ObjectKind::kMesh && lowerExtension(object.path) == ".obj") {
      for (std::string& mtl : materialLibraries(object.path)) files.push_back(std::move(mtl));
    }
    const bool denseVolume = object.kind == ObjectKind::kVolume &&
                             (!object.thresholds.empty() || !object.tfPath.empty());
    if (denseVolume) {
      auto source = sources::openVolume(object.path);  // headers only: cheap
      if (source) {
        const std::vector<std::string>& read = (*source)->info().files;
        files.insert(files.end(), read.begin(), read.end());
      }
    }
  }
  return files;
}

}  // namespace voxlink::scene
