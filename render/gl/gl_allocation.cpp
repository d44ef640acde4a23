// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/detail/gl_allocation.h"

#include <epoxy/gl.h>

namespace voxlink::render::gl {

void discardPendingGlErrors() {
  // Bounded: after a context loss some drivers report GL_CONTEXT_LOST on every call.
  for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; ++i) {
  }
}

Status checkGlAllocation(const std::string& what, const std::string& detail) {
  const GLenum e = glGetError();
  if (e == GL_NO_ERROR) return Status::ok();
  return makeError(ErrorCode::kTooLarge, "render: GL cannot allocate ", what, " (", detail,
                   "GL error 0x", std::hex, e, e == GL_OUT_OF_MEMORY ? ", out of memory" : "",
                   "); render a smaller image");
}

}  // namespace voxlink::render::gl
