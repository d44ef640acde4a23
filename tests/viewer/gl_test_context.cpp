// SPDX-License-Identifier: BSD-3-Clause
#include "tests/viewer/gl_test_context.h"

#include <cstdio>

namespace voxlink::render::testing {

using render::gl::createHeadlessContext;
using render::gl::GlContext;

GlContext* glContext() {
  static std::unique_ptr<GlContext> context = [] {
    auto c = createHeadlessContext();
    if (!c) {
      std::fprintf(stderr, "%s\n", c.message().c_str());
      return std::unique_ptr<GlContext>();
    }
    std::fprintf(stderr, "GL: %s\n", (*c)->description().c_str());
    return std::move(*c);
  }();
  return context.get();
}

}  // namespace voxlink::render::testing
