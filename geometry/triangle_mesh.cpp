// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/triangle_mesh.h"

namespace voxlink::geometry {

Bounds3 meshBounds(const TriangleMesh& mesh) {
  Bounds3 box;
  for (uint32_t v : mesh.triangles) {
    box.add(mesh.positions[3 * size_t(v)], mesh.positions[3 * size_t(v) + 1],
            mesh.positions[3 * size_t(v) + 2]);
  }
  return box;
}

}  // namespace voxlink::geometry
