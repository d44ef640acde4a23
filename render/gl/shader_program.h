// SPDX-License-Identifier: BSD-3-Clause
// GLSL programs built from shaders/*.glsl. The files are compiled into the library as strings
// at build time (render/gl/embed_shaders.cmake), so an installed `voxlink` needs no shader files;
// setting VOXLINK_SHADER_DIR makes the library read them from that directory instead (shader
// development without rebuilding). `#include "name"` is resolved here, once per file, with
// #line directives so compiler messages point back to file:line.
#pragma once

#include <epoxy/gl.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"

namespace voxlink::render::gl {

struct ShaderDefine {
  std::string name;
  std::string value;
};

struct PreprocessedShader {
  std::string text;
  std::vector<std::string> files;  // source-string number (the #line file id) -> file name
};

// Text of a shader file: from `generated` first, then VOXLINK_SHADER_DIR, then the embedded set.
std::optional<std::string> shaderFile(const std::string& name,
                                      const std::map<std::string, std::string>& generated = {});

// Resolves includes and puts the defines right after #version.
Result<PreprocessedShader> preprocessShader(const std::string& mainFile,
                                            const std::vector<ShaderDefine>& defines,
                                            const std::map<std::string, std::string>& generated);

// Rewrites "3:12(5): error" (Mesa) and "3(12) : error" (NVIDIA) into "file.glsl:12(5): error".
std::string mapShaderLog(const std::string& log, const std::vector<std::string>& files);

// One shader stage compiled from a file; compile errors name file:line. The caller owns the
// shader (linkProgram deletes it).
Result<GLuint> compileShaderStage(GLenum stage, const std::string& file,
                                  const std::vector<ShaderDefine>& defines = {},
                                  const std::map<std::string, std::string>& generated = {});

// Links the stages into a program and deletes them, linked or not. `name` and `files` (the
// stages' #line file ids, as compileShaderStage resolved them) name the program in errors.
Result<GLuint> linkProgram(const std::vector<GLuint>& stages, const std::string& name,
                           const std::vector<std::string>& files = {});

class ComputeProgram {
 public:
  static Result<ComputeProgram> build(const std::string& mainFile,
                                      const std::vector<ShaderDefine>& defines = {},
                                      const std::map<std::string, std::string>& generated = {});
  ComputeProgram() = default;
  ComputeProgram(ComputeProgram&& other) noexcept;
  ComputeProgram& operator=(ComputeProgram&& other) noexcept;
  ~ComputeProgram();

  GLuint id() const { return program_; }
  void use() const { glUseProgram(program_); }
  // -1 when the uniform does not exist or was optimized away (glUniform ignores -1).
  GLint uniform(const char* name) const { return glGetUniformLocation(program_, name); }

 private:
  GLuint program_ = 0;
};

}  // namespace voxlink::render::gl
