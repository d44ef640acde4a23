// SPDX-License-Identifier: BSD-3-Clause
// The GL ray tracer over a VoxLink file (paper, sections 3.1.4 and 5.1): the file's sections in
// storage buffers, brick skipping and per-row voxel traversal in shaders/voxlink_*.glsl.
#pragma once

#include <memory>
#include <optional>

#include "format/voxlink_file.h"
#include "render/gl/detail/section_buffers.h"
#include "render/gl/detail/shadow_cache_buffer.h"
#include "render/gl/detail/volume_renderer.h"

namespace voxlink::render::gl {

class VoxLinkRenderer : public VolumeRenderer {
 public:
  // Uploads the sections; the file may be closed afterwards. Needs a current GL context.
  static Result<std::unique_ptr<VoxLinkRenderer>> create(const format::VoxLinkFile& file,
                                                         const SectionBufferOptions& options = {});
  std::string name() const override { return "voxlink"; }
  const SectionBuffers& sections() const { return sections_; }
  // Shadow codes the fills so far set (ShadowCacheBuffer::countSetCodes); 0 before any.
  uint64_t setShadowCodes() const { return shadowCache_ ? shadowCache_->countSetCodes() : 0; }

 protected:
  std::string mainShader() const override { return "render_voxlink.comp.glsl"; }
  std::string effectsShader() const override { return "render_effects.comp.glsl"; }
  Status checkSupported(const RenderSettings& settings) const override;
  std::vector<ShaderDefine> dataDefines() const override;
  std::map<std::string, std::string> generatedFiles() const override;
  void bindData(const ComputeProgram& program) const override;
  // The sections, and the shadow cache once a frame with per-voxel shadow rays made it.
  uint64_t dataBytes() const override {
    return sections_.gpuBytes() + (shadowCache_ ? shadowCache_->bytes() : 0);
  }
  bool cachesShadows(const RenderSettings& settings) const override;
  bool marksByDefault(const RenderSettings& settings) const override;
  Status beginShadowCache(bool refill, bool clearMarks) override;
  std::string shadowFillShader() const override { return "shadow_fill.comp.glsl"; }
  void fillShadowCache(const ComputeProgram& program) const override;

 protected:
  VoxLinkRenderer(const format::VoxLinkFile& file, SectionBuffers sections);

 private:
  SectionBuffers sections_;
  format::FileHeader header_;
  std::optional<ShadowCacheBuffer> shadowCache_;
  // Per occupied brick its grid cell (occupiedBrickCells), for the shadow cache's fill pass.
  std::vector<uint32_t> brickCells_;
};

// The defines and generated include the VoxLink shaders need for a file (tests reuse them).
std::vector<ShaderDefine> voxlinkDefines(const format::FileHeader& header);

}  // namespace voxlink::render::gl
