// SPDX-License-Identifier: BSD-3-Clause
// Shader loading: includes resolved once each, defines placed after #version, compiler messages
// mapped back to the file and line they came from, and every shipped program compiling.
#include "render/gl/shader_program.h"

#include <gtest/gtest.h>

#include "render/gl/detail/volume_renderer.h"
#include "tests/viewer/gl_test_context.h"

namespace voxlink::render::gl {

namespace {

const std::map<std::string, std::string> kFiles = {
    {"main.glsl",
     "// comment before the version\n#version 450\nlayout(local_size_x = 1) in;\n"
     "#include \"a.glsl\"\n#include \"b.glsl\"\n#include \"a.glsl\"\nvoid main() {}\n"},
    {"a.glsl", "// a\nfloat fa() { return 1.0; }\n"},
    {"b.glsl", "#include \"a.glsl\"\n// b\n\nfloat fb() { return fa() BROKEN; }\n"},
    {"loop.glsl", "#version 450\n#include \"loop.glsl\"\n"},
};

TEST(ShaderProgram, IncludesOnceWithLineDirectives) {
  auto p = preprocessShader("main.glsl", {{"VXL_N", "8"}}, kFiles);
  ASSERT_TRUE(p) << p.message();
  EXPECT_EQ(p->text.rfind("#version 450\n#define VXL_N 8\n", 0), 0u) << p->text;
  EXPECT_EQ(p->files, (std::vector<std::string>{"main.glsl", "a.glsl", "b.glsl"}));
  size_t count = 0;
  for (size_t at = p->text.find("float fa()"); at != std::string::npos;
       at = p->text.find("float fa()", at + 1))
    ++count;
  EXPECT_EQ(count, 1u);
  EXPECT_NE(p->text.find("#line 1 2\n"), std::string::npos);  // b.glsl starts
  EXPECT_NE(p->text.find("#line 6 0\n"), std::string::npos);  // back in main.glsl after b
}

TEST(ShaderProgram, MissingFilesAndSelfIncludesAreErrors) {
  auto missing = preprocessShader("nope.glsl", {}, kFiles);
  EXPECT_EQ(missing.code(), ErrorCode::kIo);
  // A file including itself is included once, like any other.
  EXPECT_TRUE(preprocessShader("loop.glsl", {}, kFiles));
  EXPECT_EQ(preprocessShader("a.glsl", {}, kFiles).code(),
            ErrorCode::kInvalidArgument);  // no #version
}

TEST(ShaderProgram, LogLinesMapToFileAndLine) {
  const std::vector<std::string> files = {"main.glsl", "a.glsl", "b.glsl"};
  EXPECT_EQ(mapShaderLog("2:4(22): error: syntax error\n", files),
            "b.glsl:4(22): error: syntax error\n");
  EXPECT_EQ(mapShaderLog("1(3) : error C0000: x\n", files), "a.glsl:3 : error C0000: x\n");
  EXPECT_EQ(mapShaderLog("plain line\n", files), "plain line\n");
}

TEST(ShaderProgram, CompileErrorsNameTheIncludedFile) {
  VOXLINK_REQUIRE_GL();
  auto p = ComputeProgram::build("main.glsl", {}, kFiles);
  ASSERT_FALSE(p);
  EXPECT_NE(p.message().find("b.glsl:4"), std::string::npos) << p.message();
}

TEST(ShaderProgram, ShippedDisplayAndTestProgramsCompile) {
  VOXLINK_REQUIRE_GL();
  EXPECT_TRUE(ComputeProgram::build("display.comp.glsl"));
  EXPECT_TRUE(
      ComputeProgram::build("test_gradient_decode.comp.glsl",
                            {{"VXL_GRADIENT_TABLE_BINDING", std::to_string(kGradientTableBinding)},
                             {"VXL_RESULTS_BINDING", "0"}}));
}

}  // namespace
}  // namespace voxlink::render::gl
