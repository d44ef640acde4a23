// SPDX-License-Identifier: BSD-3-Clause
// The benchmark's peer: a dense 3D-texture ray caster with the same model (sampling, shading,
// transfer function, step) as VoxLinkRenderer. It reads every voxel of the dense source from
// two 3D textures (stored value bits in the file's stored type, polar16 gradient codes) and
// skips no empty space.
#pragma once

#include <memory>

#include "render/dense_volume.h"
#include "render/gl/detail/volume_renderer.h"

namespace voxlink::render::gl {

class DenseRenderer : public VolumeRenderer {
 public:
  // Values are mapped to stored values with `mapping`'s type, scale and offset (the VoxLink
  // file's), so both renderers classify the same bits. Needs a current GL context.
  static Result<std::unique_ptr<DenseRenderer>> create(const DenseVolume& volume,
                                                       const VolumeGeometry& mapping);
  std::string name() const override { return "dense"; }

 protected:
  std::string mainShader() const override { return "render_dense.comp.glsl"; }
  std::vector<ShaderDefine> dataDefines() const override { return {}; }
  void bindData(const ComputeProgram& program) const override;
  uint64_t dataBytes() const override { return bytes_; }

 private:
  explicit DenseRenderer(const VolumeGeometry& g) : VolumeRenderer(g) {}
  GlTexture values_;
  GlTexture gradients_;
  uint64_t bytes_ = 0;
};

}  // namespace voxlink::render::gl
