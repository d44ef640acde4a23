// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/dynamic_scene_renderer.h"

namespace voxlink::render::gl {
namespace {
// Where the ray tracer reads the layer's pool buffer i (shaders/voxlink_dynamic.glsl).
constexpr GLuint kPoolBindings[GlDynamicLayer::kMaxPoolBuffers] = {60, 50, 51, 52};
}  // namespace

Result<std::unique_ptr<DynamicSceneRenderer>> DynamicSceneRenderer::create(
    const format::VoxLinkFile& file, const GlDynamicLayer& layer, const GlDynamicSpheres* spheres) {
  if (!file.isScene())
    return makeError(ErrorCode::kUnsupported,
                     "dynamic scene: the static part must be a scene file (version 2)");
  if (file.header().surfaceMode != 0)
    return makeError(ErrorCode::kUnsupported,
                     "dynamic scene: the static part must keep one fragment per voxel "
                     "(--surface mean), as the dynamic layer does");
  VOXLINK_ASSIGN_OR_RETURN(SectionBuffers sections, SectionBuffers::upload(file));
  return std::unique_ptr<DynamicSceneRenderer>(
      new DynamicSceneRenderer(file, std::move(sections), layer, spheres));
}

DynamicSceneRenderer::DynamicSceneRenderer(const format::VoxLinkFile& file, SectionBuffers sections,
                                           const GlDynamicLayer& layer,
                                           const GlDynamicSpheres* spheres)
    : VoxLinkRenderer(file, std::move(sections)), layer_(layer), spheres_(spheres) {
  for (int a = 0; a < 3; ++a) dims_[a] = file.header().dims[a];
}

std::vector<ShaderDefine> DynamicSceneRenderer::dataDefines() const {
  std::vector<ShaderDefine> defines = VoxLinkRenderer::dataDefines();
  defines.push_back({"VXL_DYNAMIC_LAYER", "1"});
  defines.push_back({"VXL_DYN_N", std::to_string(layer_.brickSize())});
  for (ShaderDefine& d : layer_.poolDefines()) defines.push_back(std::move(d));
  if (spheres_) {
    defines.push_back({"VXL_DYN_SPHERES", "1"});
    defines.push_back({"VXL_DYN_SPHERE_N", std::to_string(spheres_->brickSize())});
  }
  return defines;
}

void DynamicSceneRenderer::bindData(const ComputeProgram& program) const {
  VoxLinkRenderer::bindData(program);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 59, layer_.brickMap());
  for (uint32_t i = 0; i < layer_.poolBuffers(); ++i)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPoolBindings[i], layer_.poolBuffer(i));
  const uint32_t n = layer_.brickSize();
  glUniform3i(program.uniform("uDynBrickGrid"), GLint((dims_[0] + n - 1) / n),
              GLint((dims_[1] + n - 1) / n), GLint((dims_[2] + n - 1) / n));
  glUniform3i(program.uniform("uDynLo"), layer_.lo()[0], layer_.lo()[1], layer_.lo()[2]);
  glUniform3i(program.uniform("uDynHi"), layer_.hi()[0], layer_.hi()[1], layer_.hi()[2]);
  if (!spheres_) return;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 53, spheres_->heads());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 54, spheres_->nodes());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 55, spheres_->spheres());
  const uint32_t m = spheres_->brickSize();
  glUniform3i(program.uniform("uDynSphereBrickGrid"), GLint((dims_[0] + m - 1) / m),
              GLint((dims_[1] + m - 1) / m), GLint((dims_[2] + m - 1) / m));
  const auto& lo = spheres_->lo();
  const auto& hi = spheres_->hi();
  glUniform3i(program.uniform("uDynSphereLo"), lo[0], lo[1], lo[2]);
  glUniform3i(program.uniform("uDynSphereHi"), hi[0], hi[1], hi[2]);
}

}  // namespace voxlink::render::gl
