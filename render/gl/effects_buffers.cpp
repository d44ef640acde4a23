// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/detail/effects_buffers.h"

#include <algorithm>

#include "render/gl/detail/gl_allocation.h"

namespace voxlink::render::gl {
namespace {

GlStorageBuffer dynamicBuffer(uint64_t bytes) {
  GlStorageBuffer b{createBuffer(), bytes};
  glNamedBufferStorage(b.buffer.id(), GLsizeiptr(bytes), nullptr,
                       GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
  return b;
}

}  // namespace

Status EffectsBuffers::resize(uint32_t width, uint32_t height) {
  if (width == width_ && height == height_ && counters_.bytes) return Status::ok();
  discardPendingGlErrors();
  const uint64_t pixels = uint64_t(width) * height;
  capacity_ = uint32_t(std::min<uint64_t>(2 * pixels + 64, kMaxRayBufferBytes / sizeof(GpuRay)));
  for (GlStorageBuffer& r : rays_) r = dynamicBuffer(uint64_t(capacity_) * sizeof(GpuRay));
  accum_ = dynamicBuffer(pixels * 4 * sizeof(uint32_t));
  counters_ = dynamicBuffer(2 * sizeof(uint32_t));
  if (Status s = checkGlAllocation(cat("the effects buffers for a ", width, "x", height, " image"));
      !s) {
    counters_ = GlStorageBuffer{};
    width_ = height_ = 0;
    return s;
  }
  width_ = width;
  height_ = height;
  return Status::ok();
}

void EffectsBuffers::clearCounters() const {
  const uint32_t zero[2] = {0, 0};
  glNamedBufferSubData(counters_.buffer.id(), 0, sizeof(zero), zero);
}

std::pair<uint32_t, uint32_t> EffectsBuffers::readCounters() const {
  uint32_t values[2] = {0, 0};
  glGetNamedBufferSubData(counters_.buffer.id(), 0, sizeof(values), values);
  return {values[0], values[1]};
}

}  // namespace voxlink::render::gl
