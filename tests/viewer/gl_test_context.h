// SPDX-License-Identifier: BSD-3-Clause
// One headless EGL context per test binary, made on first use. GL tests fail (not skip) when
// none can be made: CI renders on llvmpipe, so a missing context is a broken setup.
#pragma once

#include <gtest/gtest.h>

#include "render/gl/gl_context.h"

namespace voxlink::render::testing {

using render::gl::GlContext;

// nullptr (and a test failure) when EGL gives no GL 4.5 context.
GlContext* glContext();

}  // namespace voxlink::render::testing

#define VOXLINK_REQUIRE_GL()                                        \
  do {                                                              \
    if (::voxlink::render::testing::glContext() == nullptr)         \
      FAIL() << "no headless OpenGL 4.5 context (EGL surfaceless)"; \
  } while (0)
