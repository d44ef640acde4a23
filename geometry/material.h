// SPDX-License-Identifier: BSD-3-Clause
// A surface material as the ray tracer needs it, mapped from the mesh file's own description.
//
// MTL (Wavefront OBJ) -> Material, applied by loadMesh (mesh_loader.h):
//   name             newmtl NAME
//   color            Kd (diffuse colour)
//   opacity          d, or 1 - Tr when only Tr is given (assimp folds both into one value)
//   reflectivity     illum 3 or 5 (mirror): mean of Ks, or 1 when Ks is zero;
//                    illum 4, 6 or 7 (glass): mean of Ks (the reflected part); otherwise 0
//   transmission     illum 4, 6 or 7 (glass): 1 - d when d < 1, else 1 (MTL's d is a dissolve
//                    factor, not a transmittance: clear glass has d = 1 and leaves the split
//                    between reflection and refraction to Fresnel with Ni); otherwise 0.
//                    Tf (transmission filter) is not used.
//   refractiveIndex  Ni, kept only when transmission > 0; 1 (no refraction) otherwise
//   emission         Ke
// Other formats (PLY, STL, glTF) get what assimp reports for the same keys; a file without
// materials gets one default material (assimp's "DefaultMaterial").
#pragma once

#include <array>
#include <string>

namespace voxlink::geometry {

struct Material {
  std::string name;
  std::array<float, 3> color{0.8f, 0.8f, 0.8f};     // diffuse rgb, 0..1
  float opacity = 1.0f;                             // 0 (invisible) .. 1 (opaque)
  float reflectivity = 0.0f;                        // mirror fraction, 0..1
  float refractiveIndex = 1.0f;                     // 1 = no refraction
  float transmission = 0.0f;                        // refracted (glass) fraction, 0..1
  std::array<float, 3> emission{0.0f, 0.0f, 0.0f};  // emitted rgb radiance, unbounded
};

}  // namespace voxlink::geometry
