// SPDX-License-Identifier: BSD-3-Clause
// What the GL ray casters share: the frame's uniforms (camera, settings, volume geometry), the
// transfer-function and gradient-decoding tables, a cache of compiled program variants and the
// dispatch. VoxLinkRenderer (the sparse file) and DenseRenderer (3D textures) fill in the data.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "format/voxlink_file.h"
#include "render/camera.h"
#include "render/gl/detail/effects_buffers.h"
#include "render/gl/detail/gl_objects.h"
#include "render/gl/detail/loop_limit_retrace.h"
#include "render/gl/render_target.h"
#include "render/gl/shader_program.h"
#include "render/render_model.h"
#include "render/render_settings.h"
#include "tf/tf_table.h"
#include "tf/transfer_function.h"

namespace voxlink::render::gl {

using tf::TfTable;

// The geometry and value mapping both renderers need, in the file's terms.
struct VolumeGeometry {
  std::array<uint32_t, 3> dims{0, 0, 0};
  std::array<double, 3> spacing{1, 1, 1};
  std::array<double, 3> origin{0, 0, 0};
  StoredType valueType = StoredType::kU8;
  double valueScale = 1.0;
  double valueOffset = 0.0;
  // Voxels (of the smallest spacing) that rays spawned at a surface start off it.
  double surfaceOffsetVoxels = render::kSurfaceShadowBias;
  // The stored value bits a 16-bit file holds, [firstValueBits, firstValueBits + valueBitsCount):
  // its indexed TF table covers only those (0: every value of the type).
  uint32_t firstValueBits = 0;
  uint32_t valueBitsCount = 0;

  static VolumeGeometry of(const format::FileHeader& header);
  Box worldBox() const;
  double minSpacing() const;
};

// Storage-buffer bindings of the tables, above any the file's sections take.
inline constexpr GLuint kTfBinding = 62;
inline constexpr GLuint kGradientTableBinding = 63;
// Texture unit of the TF table read as a buffer texture (indexed tables): the last one a compute
// shader has (SectionBuffers leaves it free).
GLuint tfTextureUnit();
// Stored values of an 8-bit file: its TF table's premultiplied copy starts at this texel.
inline constexpr size_t kU8TfEntries = 256;

class VolumeRenderer {
 public:
  virtual ~VolumeRenderer() = default;

  void setTransferFunction(const tf::TransferFunction& tf);
  const tf::TransferFunction& transferFunction() const { return tf_; }
  // Renders into `target` (resized to the settings' size). Returns once the work is queued;
  // call glFinish() or target.read() to wait for it.
  Status render(const Camera& camera, const RenderSettings& settings, RenderTarget& target);
  // GPU memory of the volume data, the tables and nothing else.
  uint64_t gpuBytes() const { return dataBytes() + tfBytes_ + gradientTable_.bytes; }
  uint64_t tfBytes() const { return tfBytes_; }
  const VolumeGeometry& geometry() const { return geometry_; }
  virtual std::string name() const = 0;

  // What the last frame of the ray-traced mode (settings.effects) did: passes run (the primary
  // pass included), rays traced after the primary ones, rays the buffer had no room for.
  struct EffectsStats {
    int passes = 0;
    uint64_t secondaryRays = 0;
    uint64_t droppedRays = 0;
  };
  const EffectsStats& lastEffectsStats() const { return effectsStats_; }
  // Pixels of the last plain frame traced again because the driver's loop cap cut their rays
  // short (loop_limit_retrace.h); 0 without shadow rays.
  uint32_t lastRetracedPixels() const { return lastRetraced_; }
  // Per-voxel shadow rays (docs/shadows.md): a frame fills the cache only where the world light,
  // the transfer function or the shadow stop differ from the last fill's; a still frame, a zoom
  // or a pan reads the codes as they are. shadowFills() counts the fill passes run;
  // forgetShadowCache() makes the next such frame fill again (benchmarks time a frame with it).
  uint64_t shadowFills() const { return shadowFills_; }
  void forgetShadowCache() { filledFor_.reset(); }
  // Whether a marking frame runs before the fill, so that the fill walks only the centres the
  // frame reads (docs/shadows.md, "The marking frame"): kAuto in voxel sampling where the image
  // has fewer than half as many pixels as the file has voxel slots (the env
  // VOXLINK_SHADOW_MARK=0/1 overrides it). Marked codes hold for this view alone: a zoom or a
  // pan fills again.
  enum class ShadowMarking { kAuto, kOn, kOff };
  void setShadowMarking(ShadowMarking m) { marking_ = m; }
  // Marking frames run (each before a fill that walks only what it marked).
  uint64_t shadowMarks() const { return shadowMarks_; }

 protected:
  explicit VolumeRenderer(const VolumeGeometry& geometry);
  virtual std::string mainShader() const = 0;
  // The ray-traced mode's pass shader; empty where the data has no such mode.
  virtual std::string effectsShader() const { return {}; }
  // Refuses settings the data cannot be rendered with (called before every frame).
  virtual Status checkSupported(const RenderSettings&) const { return Status::ok(); }
  virtual std::vector<ShaderDefine> dataDefines() const = 0;
  virtual std::map<std::string, std::string> generatedFiles() const { return {}; }
  virtual void bindData(const ComputeProgram& program) const = 0;
  virtual uint64_t dataBytes() const = 0;
  // Whether frames with these settings read the shadow cache (shaders/shadow_cache.glsl); then
  // before each such frame beginShadowCache() binds it, and where its codes are stale (`refill`)
  // first clears it, and fillShadowCache() then runs the fill pass (shadowFillShader(), its
  // uniforms and tables set) that sets every code the frame reads. The codes depend on the world
  // light, the TF and the shadow stop only (the ShadowFill key): the data never change after
  // upload (dynamic scenes' layers move, but scenes cast per-sample rays), and the fill walks the
  // same nearest-voxel shadow rays whatever the frame's sampling.
  virtual bool cachesShadows(const RenderSettings&) const { return false; }
  // ShadowMarking::kAuto's choice for these settings.
  virtual bool marksByDefault(const RenderSettings&) const { return false; }
  // `clearMarks`: a marking frame follows.
  virtual Status beginShadowCache(bool /*refill*/, bool /*clearMarks*/) { return Status::ok(); }
  virtual std::string shadowFillShader() const { return {}; }
  virtual void fillShadowCache(const ComputeProgram&) const {}

 private:
  // Program variants: the plain frame, the shadow cache's fill pass before it, and the
  // ray-traced mode's primary pass, secondary pass and resolve (volume_renderer_effects.cpp).
  // kShadowMark: the plain frame marking the centres it reads; kShadowFillMarked: the fill of
  // those.
  enum class Pass {
    kPlain,
    kEffectsPrimary,
    kEffectsSecondary,
    kEffectsResolve,
    kShadowFill,
    kShadowMark,
    kShadowFillMarked
  };
  bool marks(const RenderSettings& s) const;
  Result<const ComputeProgram*> program(const RenderSettings& settings, Pass pass = Pass::kPlain);
  Status renderEffects(const Camera& camera, const RenderSettings& settings, RenderTarget& target);
  void setEffectsUniforms(const ComputeProgram& p, const Camera& camera,
                          const RenderSettings& s) const;
  void bindTables(const ComputeProgram& p) const;
  // Whether the TF texels hold a premultiplied copy (8-bit files; VXL_TF_PREMULTIPLIED).
  bool premultipliedTf() const;
  // Whether the TF texels hold only the file's stored values (16-bit files; VXL_TF_FIRST).
  bool slicesTf() const;
  void setFrameUniforms(const ComputeProgram& p, const Camera& camera, const RenderSettings& s,
                        uint32_t width, uint32_t height) const;
  struct MarkedView;
  // The camera and sampling uniforms, as setFrameUniforms sets them.
  MarkedView markedView(const Camera& camera, const RenderSettings& s, uint32_t width,
                        uint32_t height) const;

  // What the shadow cache's codes were filled for: the light as the fill's uniform held it, and
  // for marked codes the view and what decides the samples a frame takes.
  struct MarkedView {
    glm::vec3 eye{0.0f}, forward{0.0f}, right{0.0f}, up{0.0f};
    uint32_t width = 0, height = 0;
    int sampling = 0;
    float step = 0.0f, stopTransmittance = 0.0f;
    bool operator==(const MarkedView&) const = default;
  };
  struct ShadowFill {
    glm::vec3 toLight{0.0f};
    float stop = 0.0f;
    uint64_t tfGeneration = 0;
    bool marked = false;
    MarkedView view;  // zero where not marked
    bool operator==(const ShadowFill&) const = default;
  };
  ShadowMarking marking_ = ShadowMarking::kAuto;
  uint64_t shadowMarks_ = 0;

  VolumeGeometry geometry_;
  tf::TransferFunction tf_;
  uint64_t tfGeneration_ = 0;  // bumped by every setTransferFunction
  std::optional<ShadowFill> filledFor_;
  uint64_t shadowFills_ = 0;
  TfTable table_;
  GlStorageBuffer tfBuffer_;
  GlTexture tfTexels_;  // tfBuffer_ as a buffer texture of RGBA texels
  uint64_t tfBytes_ = 0;
  GlStorageBuffer gradientTable_;
  std::map<std::tuple<int, bool, int, int, bool, int, bool>, ComputeProgram> programs_;
  EffectsBuffers effects_;
  EffectsStats effectsStats_;
  LoopLimitRetrace retrace_;
  uint32_t lastRetraced_ = 0;
};

}  // namespace voxlink::render::gl
