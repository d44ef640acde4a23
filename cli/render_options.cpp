// SPDX-License-Identifier: BSD-3-Clause
#include "cli/render_options.h"

#include <cstdio>

#include "tf/tf_presets.h"

namespace voxlink::cli {

void RenderOptions::add(CLI::App* cmd, bool withSize) {
  if (withSize) cmd->add_option("--size", size, "Image size WxH")->capture_default_str();
  cmd->add_option("--tf", tfPath, "Transfer function JSON (docs/transfer-function.md)");
  cmd->add_option("--tf-preset", tfPreset,
                  "Built-in transfer function stretched over the stored value range")
      ->check(CLI::IsMember(tf::tfPresetNames()));
  cmd->add_option("--camera", camera,
                  "AZ,EL[,DIST[,FOV]]: azimuth and elevation in degrees, distance "
                  "(1 frames the volume), vertical field of view (default 30,20,1,30)");
  cmd->add_option("--up", up,
                  "World axis pointing up on screen (default z, or the scene file's camera)")
      ->check(CLI::IsMember({"y", "z", "-y", "-z"}));
  cmd->add_option("--sampling", sampling, "voxel (nearest, exact chords) or trilinear")
      ->check(CLI::IsMember({"voxel", "trilinear"}))
      ->capture_default_str();
  cmd->add_option("--step", step, "Trilinear step in units of the smallest voxel spacing")
      ->capture_default_str();
  cmd->add_option(
         "--termination-alpha", terminationAlpha,
         "Rays stop once their accumulated opacity reaches this, in (0, 1] (ParaView 5.11: "
         "1 - 1/255)")
      ->capture_default_str();
  cmd->add_flag("--shadows", shadows, "Shadow rays towards the light");
  cmd->add_option("--shadow-rays", shadowRays,
                  "With --shadows: per-voxel (one ray per voxel centre per frame, shared; the "
                  "default for volume files) or per-sample (one per sample; scenes)")
      ->check(CLI::IsMember({"per-sample", "per-voxel"}));
  cmd->add_flag("--no-shading", noShading, "Unlit colours (no Phong shading)");
  cmd->add_option(
         "--effects", effects,
         "Ray-traced scene mode: reflect, refract, shadows (comma-separated), all or none; "
         "lit by the scene file's lights (docs/effects.md)")
      ->capture_default_str();
  cmd->add_option("--max-bounces", maxBounces,
                  "Secondary-ray generations in the ray-traced mode (0-15)")
      ->capture_default_str();
  cmd->add_option("--steps-per-pass", stepsPerPass,
                  "Ray-traced mode on the GPU: occupied bricks a ray crosses per pass before it "
                  "waits for the next (does not change the image)")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--background", background, "Background colour R,G,B in [0, 1] (linear)")
      ->capture_default_str();
}

void SourceOptions::add(CLI::App* cmd) {
  cmd->add_option("--source", path,
                  "Dense source volume (default: the one the file's META records)");
  cmd->add_option("--source-dims", dims, "X,Y,Z of a raw --source");
  cmd->add_option("--source-type", type, "Element type of a raw --source (u8, i16, f32, ...)");
}

Result<sources::OpenOptions> SourceOptions::openOptions() const {
  sources::OpenOptions o;
  if (!dims.empty()) {
    std::array<uint32_t, 3> d{};
    char c1 = 0, c2 = 0, extra = 0;
    if (std::sscanf(dims.c_str(), "%u%c%u%c%u%c", &d[0], &c1, &d[1], &c2, &d[2], &extra) != 5 ||
        c1 != ',' || c2 != ',')
      return makeError(ErrorCode::kInvalidArgument, "--source-dims: expected X,Y,Z, got '", dims,
                       "'");
    o.dims = d;
  }
  if (!type.empty()) {
    const auto t = parseScalarName(type);
    if (!t)
      return makeError(ErrorCode::kInvalidArgument, "--source-type: unknown type '", type, "'");
    o.type = *t;
  }
  if (o.dims && o.type) o.format = "raw";
  return o;
}

}  // namespace voxlink::cli
