// SPDX-License-Identifier: BSD-3-Clause
// GPU buffers of the ray-traced scene mode (paper, section 5.2.2): two ray buffers (one pass
// reads the rays the previous pass spawned into the other), an atomic counter pair (rays
// spawned, rays dropped for want of room) and the per-pixel fixed-point accumulator.
#pragma once

#include <cstdint>

#include "base/error.h"
#include "render/gl/detail/gl_objects.h"

namespace voxlink::render::gl {

// One ray, std430: shaders/voxlink_effects.glsl, GpuRay.
struct GpuRay {
  float origin[3];
  float weight;
  float direction[3];
  uint32_t pixelDepth;  // pixel index | medium << 26 | generation << 28
};
static_assert(sizeof(GpuRay) == 32);

// Storage-buffer bindings, above the file's sections and below the tables (volume_renderer.h).
inline constexpr GLuint kRaysInBinding = 56;
inline constexpr GLuint kRaysOutBinding = 57;
inline constexpr GLuint kAccumBinding = 58;
// Fixed point of the accumulator: this many units per 1.0 (shaders/render_effects.comp.glsl).
inline constexpr double kAccumScale = 1048576.0;
// One storage-buffer binding holds at most 128 MiB on llvmpipe.
inline constexpr uint64_t kMaxRayBufferBytes = 128ull << 20;
// A ray names its pixel in 26 bits: the ray-traced mode renders at most this many pixels.
inline constexpr uint64_t kMaxEffectsPixels = 1ull << 26;

class EffectsBuffers {
 public:
  // Sizes the buffers for an image (keeps them when the size is unchanged). Each ray buffer holds
  // two rays per pixel, within kMaxRayBufferBytes.
  // Fails (kTooLarge) when GL cannot allocate the buffers for that many pixels.
  Status resize(uint32_t width, uint32_t height);
  uint32_t rayCapacity() const { return capacity_; }
  const GlStorageBuffer& rays(int i) const { return rays_[i]; }
  const GlStorageBuffer& accum() const { return accum_; }
  GLuint counters() const { return counters_.buffer.id(); }
  void clearCounters() const;
  // Reads the counters back (waits for the GPU): rays spawned, rays dropped.
  std::pair<uint32_t, uint32_t> readCounters() const;
  uint64_t bytes() const { return rays_[0].bytes + rays_[1].bytes + accum_.bytes; }

 private:
  uint32_t width_ = 0, height_ = 0, capacity_ = 0;
  GlStorageBuffer rays_[2];
  GlStorageBuffer accum_;
  GlStorageBuffer counters_;
};

}  // namespace voxlink::render::gl
