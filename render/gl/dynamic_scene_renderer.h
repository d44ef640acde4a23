// SPDX-License-Identifier: BSD-3-Clause
// The GL ray tracer over a dynamic scene (docs/dynamic-scenes.md): the static scene file as
// VoxLinkRenderer draws it, plus the dynamic layer (gl_dynamic_layer.h) the moving meshes were
// voxelized into this frame and, where sphere sets move, their sphere lists (gl_dynamic_spheres.h);
// each ray takes the nearest of them (shaders/voxlink_dynamic.glsl).
// Shadow rays (shaders/voxlink_shadow.glsl) and the ray-traced mode's rays
// (shaders/render_effects.comp.glsl) test the layer too.
#pragma once

#include <memory>

#include "render/gl/gl_dynamic_layer.h"
#include "render/gl/gl_dynamic_spheres.h"
#include "render/gl/voxlink_renderer.h"

namespace voxlink::render::gl {

class DynamicSceneRenderer : public VoxLinkRenderer {
 public:
  // `layer` (and `spheres`, null where no sphere set moves) must outlive the renderer; their
  // update() before each render() is what is drawn.
  static Result<std::unique_ptr<DynamicSceneRenderer>> create(
      const format::VoxLinkFile& file, const GlDynamicLayer& layer,
      const GlDynamicSpheres* spheres = nullptr);
  std::string name() const override { return "voxlink-dynamic"; }

 protected:
  std::vector<ShaderDefine> dataDefines() const override;
  void bindData(const ComputeProgram& program) const override;

 private:
  DynamicSceneRenderer(const format::VoxLinkFile& file, SectionBuffers sections,
                       const GlDynamicLayer& layer, const GlDynamicSpheres* spheres);
  const GlDynamicLayer& layer_;
  const GlDynamicSpheres* spheres_;
  std::array<uint32_t, 3> dims_;
};

}  // namespace voxlink::render::gl
