// SPDX-License-Identifier: BSD-3-Clause
// What voxelization costs at silhouettes and edges, where PSNR over the whole image hides it:
// for every pixel, the first surface its primary ray meets (its material, or none). A pixel's
// first hit differs when the two scenes show a different object or material there, or one shows
// background (coverage). The edge mask is every pixel whose first hit differs from a 4-neighbour's
// in either image: silhouettes and material borders, where a voxel-sized shift shows.
#pragma once

#include <cstdint>
#include <vector>

#include "base/error.h"
#include "render/camera.h"
#include "render/image.h"
#include "render/scene_walker.h"

namespace voxlink::exact {

inline constexpr int32_t kNoHit = -1;

// Per pixel (row 0 at the top) the material of the first surface event, or kNoHit.
struct FirstHitMap {
  uint32_t width = 0, height = 0;
  std::vector<int32_t> material;
};

FirstHitMap firstHits(const render::SceneWalker& scene, const render::Camera& camera,
                      uint32_t width, uint32_t height);

struct EdgeError {
  double firstHitMismatch = 0;  // share of pixels whose first hit differs
  double coverageMismatch = 0;  // share of pixels where one image hits and the other does not
  double edgeShare = 0;         // share of pixels in the edge mask
  double edgePsnr = 0;          // PSNR (RGB clamped to [0, 1]) over the edge mask
  double interiorPsnr = 0;      // PSNR over the rest
};

// `test` and `truth` are the images, `a` and `b` their first-hit maps; all of one size.
Result<EdgeError> compareEdges(const render::Image& test, const render::Image& truth,
                               const FirstHitMap& a, const FirstHitMap& b);

}  // namespace voxlink::exact
