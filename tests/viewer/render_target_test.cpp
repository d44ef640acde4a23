// SPDX-License-Identifier: BSD-3-Clause
// A render target GL cannot allocate fails at once, in one line naming the size, instead of a
// compute pass writing into nothing for a minute and then reporting a bare GL error code; the
// target stays usable at a size that fits.
#include "render/gl/render_target.h"

#include <gtest/gtest.h>

#include <cstring>

#include "tests/viewer/gl_test_context.h"

namespace voxlink::render::gl {

namespace {

TEST(RenderTarget, ImageGlCannotAllocateFailsInOneLine) {
  VOXLINK_REQUIRE_GL();
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  // llvmpipe refuses textures above about 2 GiB; a GPU may hold this one.
  if (renderer == nullptr || std::strstr(renderer, "llvmpipe") == nullptr)
    GTEST_SKIP() << "the allocation limit is llvmpipe's; renderer: " << (renderer ? renderer : "?");
  RenderTarget target;
  const Status refused = target.resize(16384, 16384);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.code(), ErrorCode::kTooLarge);
  EXPECT_EQ(refused.message(),
            "render: GL cannot allocate the 16384x16384 image (RGBA32F, 4294 MB; GL error 0x505, "
            "out of memory); render a smaller image");
  EXPECT_EQ(target.width(), 0u);
  ASSERT_TRUE(target.resize(64, 32));
  EXPECT_EQ(target.read().width, 64u);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

}  // namespace
}  // namespace voxlink::render::gl
