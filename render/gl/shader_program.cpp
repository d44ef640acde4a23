// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/shader_program.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace voxlink::render::gl {

// Generated at build time from shaders/*.glsl (render/gl/embed_shaders.cmake).
const std::map<std::string, std::string>& embeddedShaderFiles();

namespace {

constexpr int kMaxIncludeDepth = 32;

struct Preprocessor {
  const std::map<std::string, std::string>& generated;
  PreprocessedShader out;
  std::set<std::string> included;

  Status expand(const std::string& name, int depth, const std::vector<ShaderDefine>* defines) {
    if (depth > kMaxIncludeDepth)
      return makeError(ErrorCode::kInvalidArgument, name, ": includes nest deeper than ",
                       kMaxIncludeDepth);
    auto text = shaderFile(name, generated);
    if (!text) return makeError(ErrorCode::kIo, name, ": shader file not found");
    included.insert(name);
    const int id = static_cast<int>(out.files.size());
    out.files.push_back(name);
    std::istringstream in(*text);
    std::string line;
    int lineNo = 0;
    bool versionSeen = defines == nullptr;  // only the main file has (and needs) #version
    if (versionSeen) out.text += cat("#line 1 ", id, "\n");
    static const std::regex includeRe(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
    while (std::getline(in, line)) {
      ++lineNo;
      std::smatch m;
      if (!versionSeen && line.rfind("#version", 0) == 0) {
        // #version must come first: restart the text with it, the defines, then the rest.
        out.text = line + "\n";
        for (const ShaderDefine& d : *defines)
          out.text += cat("#define ", d.name, " ", d.value, "\n");
        out.text += cat("#line ", lineNo + 1, " ", id, "\n");
        versionSeen = true;
      } else if (std::regex_match(line, m, includeRe)) {
        const std::string child = m[1];
        if (!included.count(child)) {
          Status s = expand(child, depth + 1, nullptr);
          if (!s) return makeError(s.code(), name, ":", lineNo, ": ", s.message());
          out.text += cat("#line ", lineNo + 1, " ", id, "\n");
        } else {
          out.text += "\n";
        }
      } else {
        out.text += line + "\n";
      }
    }
    if (!versionSeen) return makeError(ErrorCode::kInvalidArgument, name, ": no #version line");
    return Status::ok();
  }
};

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) return {};
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

std::optional<std::string> shaderFile(const std::string& name,
                                      const std::map<std::string, std::string>& generated) {
  if (auto it = generated.find(name); it != generated.end()) return it->second;
  if (const char* dir = std::getenv("VOXLINK_SHADER_DIR"); dir && *dir) {
    std::ifstream probe(std::string(dir) + "/" + name);
    if (probe) return readFile(std::string(dir) + "/" + name);
  }
  const auto& embedded = embeddedShaderFiles();
  if (auto it = embedded.find(name); it != embedded.end()) return it->second;
  return std::nullopt;
}

Result<PreprocessedShader> preprocessShader(const std::string& mainFile,
                                            const std::vector<ShaderDefine>& defines,
                                            const std::map<std::string, std::string>& generated) {
  Preprocessor p{generated, {}, {}};
  VOXLINK_RETURN_IF_ERROR(p.expand(mainFile, 0, &defines));
  return std::move(p.out);
}

std::string mapShaderLog(const std::string& log, const std::vector<std::string>& files) {
  static const std::regex mesa(R"(^(\d+):(\d+)\((\d+)\))");
  static const std::regex nvidia(R"(^(\d+)\((\d+)\))");
  std::istringstream in(log);
  std::string line, out;
  while (std::getline(in, line)) {
    std::smatch m;
    auto name = [&](const std::string& id) {
      const size_t i = std::stoul(id);
      return i < files.size() ? files[i] : "source " + id;
    };
    if (std::regex_search(line, m, mesa))
      line = name(m[1]) + ":" + m[2].str() + "(" + m[3].str() + ")" + m.suffix().str();
    else if (std::regex_search(line, m, nvidia))
      line = name(m[1]) + ":" + m[2].str() + m.suffix().str();
    out += line + "\n";
  }
  return out;
}

namespace {

// The info log of a shader or program, which GL hands out by length.
template <typename GetIv, typename GetLog>
std::string infoLog(GLuint object, GetIv getIv, GetLog getLog) {
  GLint length = 0;
  getIv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(size_t(std::max(length, 1)), '\0');
  getLog(object, length, nullptr, log.data());
  return log.c_str();  // up to the terminating zero
}

Result<GLuint> compileText(GLenum stage, const std::string& file,
                           const PreprocessedShader& source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.text.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = infoLog(shader, glGetShaderiv, glGetShaderInfoLog);
    glDeleteShader(shader);
    return makeError(ErrorCode::kInvalidArgument, file, ": GLSL compile error:\n",
                     mapShaderLog(log, source.files));
  }
  return shader;
}

}  // namespace

Result<GLuint> compileShaderStage(GLenum stage, const std::string& file,
                                  const std::vector<ShaderDefine>& defines,
                                  const std::map<std::string, std::string>& generated) {
  VOXLINK_ASSIGN_OR_RETURN(PreprocessedShader source, preprocessShader(file, defines, generated));
  return compileText(stage, file, source);
}

Result<GLuint> linkProgram(const std::vector<GLuint>& stages, const std::string& name,
                           const std::vector<std::string>& files) {
  const GLuint program = glCreateProgram();
  for (GLuint stage : stages) glAttachShader(program, stage);
  glLinkProgram(program);
  for (GLuint stage : stages) glDeleteShader(stage);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = infoLog(program, glGetProgramiv, glGetProgramInfoLog);
    glDeleteProgram(program);
    return makeError(ErrorCode::kInvalidArgument, name, ": GLSL link error:\n",
                     mapShaderLog(log, files));
  }
  return program;
}

Result<ComputeProgram> ComputeProgram::build(const std::string& mainFile,
                                             const std::vector<ShaderDefine>& defines,
                                             const std::map<std::string, std::string>& generated) {
  VOXLINK_ASSIGN_OR_RETURN(PreprocessedShader source,
                           preprocessShader(mainFile, defines, generated));
  VOXLINK_ASSIGN_OR_RETURN(GLuint shader, compileText(GL_COMPUTE_SHADER, mainFile, source));
  ComputeProgram program;
  VOXLINK_ASSIGN_OR_RETURN(program.program_, linkProgram({shader}, mainFile, source.files));
  return program;
}

ComputeProgram::ComputeProgram(ComputeProgram&& other) noexcept : program_(other.program_) {
  other.program_ = 0;
}

ComputeProgram& ComputeProgram::operator=(ComputeProgram&& other) noexcept {
  std::swap(program_, other.program_);
  return *this;
}

ComputeProgram::~ComputeProgram() {
  if (program_) glDeleteProgram(program_);
}

}  // namespace voxlink::render::gl
