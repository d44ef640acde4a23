// A VoxLink file's sections in GPU storage buffers, uploaded unchanged. A section larger than
// one storage block allows (GL_MAX_SHADER_STORAGE_BLOCK_SIZE: 128 MiB on llvmpipe) is split into
// chunks of a power-of-two word count, each on its own binding; the generated GLSL
// (voxlink_sections.glsl) picks the chunk from the word index.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "format/voxlink_file.h"
#include "viewer/gl/gl_objects.h"

namespace voxlink::viewer {

struct SectionBufferOptions {
  // Chunk size limit; 0 asks the context (GL_MAX_SHADER_STORAGE_BLOCK_SIZE). Tests set it small
  // to exercise the split path. Rounded down to a power of two bytes, at least 64.
  uint64_t maxChunkBytes = 0;
  GLuint firstBinding = 0;
  // Storage blocks the shader needs besides the sections (the renderer's TF, gradient table and
  // brick bounds).
  uint32_t reservedBlocks = 3;
};

class SectionBuffers {
 public:
  static Result<SectionBuffers> upload(const format::VoxLinkFile& file,
                                       const SectionBufferOptions& options = {});

  // Binds every chunk to its storage-buffer binding.
  void bind() const;
  // Buffer declarations and the word accessors occWord() ... gradWord() for the shaders.
  const std::string& glsl() const { return glsl_; }
  uint64_t gpuBytes() const { return gpuBytes_; }
  uint32_t bindingCount() const { return static_cast<uint32_t>(chunks_.size()); }

 private:
  struct Chunk {
    GlBuffer buffer;
    GLuint binding;
  };
  std::vector<Chunk> chunks_;
  std::string glsl_;
  uint64_t gpuBytes_ = 0;
};

}  // namespace voxlink::viewer
