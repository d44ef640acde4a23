// SPDX-License-Identifier: BSD-3-Clause
// A VoxLink file in GPU buffers: its voxel sections as words derived at load time, ROWS and MASK
// as row words (row_words.h: a row's mask and start in one word; with row aprons on GPUs 4 rows
// in one group of two words; as they are for 32^3 bricks),
// GRAD as voxel words (voxel_words.h: decoded gradient directions, with the values of 8-bit
// files; VALU goes up as it is only for wider values), and in
// place of its brick sections (BOCC, BRNK, BVOX) brick tables derived from them when it is
// loaded (render/brick_lookup.h, brick_bounds.h): an occupied index per brick, the box of
// cells samples can meet voxels in per dual brick, and per occupied brick its box and first
// voxel. The shaders read a brick's occupied index, box and first voxel in two reads instead of
// four.
// The shaders read every buffer through a buffer texture (texelFetch): on llvmpipe a storage
// buffer read is a scalar loop over the SIMD lanes, a texel fetch a gather, measured 2.5 times
// cheaper. An array larger than one buffer texture may address (GL_MAX_TEXTURE_BUFFER_SIZE
// texels) is split into chunks of a power-of-two element count, each on its own texture unit;
// the generated GLSL (voxlink_sections.glsl) picks the chunk from the element index.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "format/voxlink_file.h"
#include "render/gl/detail/gl_objects.h"

namespace voxlink::render::gl {

struct SectionBufferOptions {
  // Chunk size limit; 0 takes what the context allows. Tests set it small to exercise the split
  // path. Rounded down to a power of two bytes, at least 64.
  uint64_t maxChunkBytes = 0;
  GLuint firstUnit = 0;  // texture unit of the first chunk
  // Rows with aprons as row groups (row_words.h: half the bytes, a costlier fetch): kAuto takes
  // them unless the GL renderer is a CPU rasterizer (llvmpipe, softpipe, SwiftShader), or as
  // the environment variable VOXLINK_ROW_GROUPS (0 or 1) says.
  enum class RowGroups { kAuto, kOn, kOff };
  RowGroups rowGroups = RowGroups::kAuto;
};

class SectionBuffers {
 public:
  static Result<SectionBuffers> upload(const format::VoxLinkFile& file,
                                       const SectionBufferOptions& options = {});

  // Binds every chunk to its texture unit.
  void bind() const;
  // Sampler declarations and the accessors rowGroup() (row aprons on GPUs: VXL_ROW_GROUPS) or
  // rowWord() (or rowsWord() and maskWord()), voxelWord(), valuWord() (wider values only),
  // brickIndexWord(), dualBoxWord(), dualIndexWords() (files below 65535 occupied bricks:
  // VXL_DUAL_INDICES) and brickEntry() for the shaders.
  const std::string& glsl() const { return glsl_; }
  uint64_t gpuBytes() const { return gpuBytes_; }
  uint32_t bindingCount() const { return static_cast<uint32_t>(chunks_.size()); }
  // Voxel words, so the range of the voxel indices the shaders see: the file's voxel count, plus
  // the apron's copies where row words have one (row_words.h).
  uint64_t voxelSlots() const { return voxelSlots_; }
  // Whether row words carry an apron (VXL_ROW_APRON, row_words.h).
  bool rowApron() const { return rowApron_; }
  // Whether those rows went up as row groups (VXL_ROW_GROUPS).
  bool rowGroups() const { return rowGroups_; }
  // The texture unit after the last chunk's.
  GLuint endUnit() const { return chunks_.empty() ? 0 : chunks_.back().unit + 1; }

 private:
  struct Chunk {
    GlBuffer buffer;
    GlTexture texture;  // the buffer as a buffer texture
    GLuint unit;
  };
  std::vector<Chunk> chunks_;
  std::string glsl_;
  uint64_t gpuBytes_ = 0;
  uint64_t voxelSlots_ = 0;
  bool rowApron_ = false;
  bool rowGroups_ = false;
};

}  // namespace voxlink::render::gl
