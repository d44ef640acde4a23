// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/detail/loop_limit_retrace.h"

#include <algorithm>

namespace voxlink::render::gl {

namespace {
// The list's layout (shaders/render_main.glsl, VxlRetrace): two counters, then one word a pixel.
constexpr GLsizeiptr kCounterBytes = 2 * sizeof(uint32_t);
}  // namespace

void LoopLimitRetrace::begin(const ComputeProgram& program, uint32_t width, uint32_t height) {
  const uint64_t pixels = uint64_t(width) * height;
  if (!buffer_ || capacity_ < pixels) {
    buffer_ = createBuffer();
    glNamedBufferData(buffer_.id(), kCounterBytes + GLsizeiptr(pixels * sizeof(uint32_t)), nullptr,
                      GL_DYNAMIC_COPY);
    capacity_ = pixels;
  }
  const uint32_t zero[2] = {0, 0};
  glNamedBufferSubData(buffer_.id(), 0, kCounterBytes, zero);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRetraceBinding, buffer_.id());
  glUniform1i(program.uniform("uLoopProbe"), kLoopProbeIterations);
  glUniform1ui(program.uniform("uRetraceItems"), 0u);
}

Result<uint32_t> LoopLimitRetrace::finish(const ComputeProgram& program,
                                          const std::string& renderer) {
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  uint32_t counters[2] = {0, 0};
  glGetNamedBufferSubData(buffer_.id(), 0, kCounterBytes, counters);
  const uint32_t listed = uint32_t(std::min<uint64_t>(counters[0], capacity_));
  if (listed == 0) return 0u;
  // 8 listed pixels a work group of 64 invocations: one in each run of 8 (a SIMD vector).
  glUniform1ui(program.uniform("uRetraceItems"), listed);
  glDispatchCompute((listed + 7) / 8, 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                  GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  glGetNamedBufferSubData(buffer_.id(), 0, kCounterBytes, counters);
  if (counters[1] > 0)
    return makeError(ErrorCode::kUnsupported, "render (", renderer, " renderer): ", counters[1],
                     " of ", listed,
                     " pixels need more loop iterations than the GL driver runs in one shader "
                     "invocation (llvmpipe: 65535), even traced alone; the image would be wrong");
  return listed;
}

}  // namespace voxlink::render::gl
