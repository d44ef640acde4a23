// SPDX-License-Identifier: BSD-3-Clause
// `voxlink bench-render --animate SCENE.json`: the paper's Table 2 in one process. Per grid
// resolution and brick size the static objects are voxelized once; every frame the animated
// meshes are re-voxelized on the GPU (render/gl/dynamic_scene.h) and the frame is ray traced;
// voxelize and render times per frame give the median, p95 and frames per second.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "cli/output_options.h"
#include "render/render_options.h"

namespace voxlink::cli {

struct AnimateBenchOptions {
  std::string scenePath;
  std::vector<std::array<uint32_t, 2>> sizes;
  std::vector<uint32_t> resolutions;  // empty: the scene file's
  std::vector<uint32_t> bricks;       // empty: the scene file's
  uint32_t frames = 60;               // timed frames over one period (or the keys' span)
  std::string pictures;               // directory for each run's first frame, or empty
};

// Prints the table; returns the exit status (errors printed as one line).
int runAnimateBenchmark(const AnimateBenchOptions& options, const render::RenderOptions& render,
                        const OutputOptions& out);

}  // namespace voxlink::cli
