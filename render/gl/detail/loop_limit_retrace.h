// SPDX-License-Identifier: BSD-3-Clause
// Frames with shadow rays on drivers that cap a shader's loops: llvmpipe (Mesa's gallivm) ends
// every loop of an invocation, silently, once the loops of its SIMD vector (8 pixels) have run
// LP_MAX_TGSI_LOOP_ITERATIONS (65535) iterations together. A primary ray with a shadow ray per
// sample can need more, and the frame then showed pixels whose rays stopped part way (issue 29:
// 51 dB instead of 71 dB on the foot CT). shaders/render_main.glsl runs a loop of a known count
// after each ray: if it ran short, the cap was reached and the pixel is listed. The listed pixels
// are traced again, one per SIMD vector, so each gets the vector's whole budget; one cut short
// even then fails the frame instead of showing a wrong value.
#pragma once

#include <cstdint>

#include "base/error.h"
#include "render/gl/detail/gl_objects.h"
#include "render/gl/shader_program.h"

namespace voxlink::render::gl {

// Storage-buffer binding of the list (VXL_RETRACE_BINDING), above the effects buffers and the
// dynamic layer's (59, 60) and below the tables (volume_renderer.h).
inline constexpr GLuint kRetraceBinding = 61;
// Iterations of the probe loop (uLoopProbe): two, so a capped loop (one pass) shows.
inline constexpr int kLoopProbeIterations = 2;

class LoopLimitRetrace {
 public:
  // Before the full pass: sizes the list for the image, empties it, binds it and sets the
  // program's uniforms for the full pass.
  void begin(const ComputeProgram& program, uint32_t width, uint32_t height);
  // After the full pass: traces the listed pixels again (with `program`, still in use) and
  // returns how many there were; fails (kUnsupported) when one was cut short again.
  Result<uint32_t> finish(const ComputeProgram& program, const std::string& renderer);

 private:
  GlBuffer buffer_;
  uint64_t capacity_ = 0;  // pixels the list holds
};

}  // namespace voxlink::render::gl
