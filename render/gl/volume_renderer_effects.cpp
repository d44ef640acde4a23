// SPDX-License-Identifier: BSD-3-Clause
// The ray-traced scene mode's frame (paper, section 5.2.2): a primary pass, then passes over the
// rays the previous pass spawned (their count read back from the atomic counter, as the paper's
// host starts each batch) until none is left or the bounce limit is reached, then the resolve.
#include <algorithm>
#include <cmath>
#include <vector>

#include "render/gl/detail/volume_renderer.h"
#include "render/render_model.h"

namespace voxlink::render::gl {

void VolumeRenderer::setEffectsUniforms(const ComputeProgram& p, const Camera& camera,
                                        const RenderSettings& s) const {
  glUniform1i(p.uniform("uReflect"), s.effects.reflect ? 1 : 0);
  glUniform1i(p.uniform("uRefract"), s.effects.refract ? 1 : 0);
  glUniform1i(p.uniform("uMaxBounces"), s.effects.maxBounces);
  glUniform1i(p.uniform("uStepsPerPass"), std::max(1, s.effects.stepsPerPass));
  glUniform1f(p.uniform("uMinWeight"), float(1.0 - s.terminationAlpha));
  glUniform1f(p.uniform("uSurfaceOffset"),
              float(geometry_.surfaceOffsetVoxels * geometry_.minSpacing()));
  glUniform1ui(p.uniform("uRayCapacity"), effects_.rayCapacity());
  std::vector<Light> lights = s.lights;
  if (lights.empty()) {
    const auto& l = s.shading.lightDirection;
    const glm::dvec3 w =
        glm::normalize(camera.toWorld(glm::normalize(glm::dvec3(l[0], l[1], l[2]))));
    lights.push_back(Light{{w.x, w.y, w.z}, {1, 1, 1}, /*directional=*/true});
  }
  std::vector<float> positions, radiances;
  for (const Light& l : lights) {
    for (int a = 0; a < 3; ++a) {
      positions.push_back(float(l.position[a]));
      radiances.push_back(float(l.radiance[a]));
    }
    positions.push_back(l.directional ? 1.0f : 0.0f);
  }
  glUniform1i(p.uniform("uLightCount"), GLint(lights.size()));
  glUniform4fv(p.uniform("uLightPosition"), GLsizei(lights.size()), positions.data());
  glUniform3fv(p.uniform("uLightRadiance"), GLsizei(lights.size()), radiances.data());
}

Status VolumeRenderer::renderEffects(const Camera& camera, const RenderSettings& settings,
                                     RenderTarget& target) {
  if (effectsShader().empty())
    return makeError(ErrorCode::kUnsupported, name(),
                     ": reflection, refraction and shadow rays (--effects) need a VoxLink file");
  if (settings.sampling != Sampling::kVoxel)
    return makeError(ErrorCode::kUnsupported, name(),
                     ": the ray-traced mode (--effects) uses voxel sampling; drop --sampling "
                     "trilinear");
  VOXLINK_ASSIGN_OR_RETURN(const ComputeProgram* primary, program(settings, Pass::kEffectsPrimary));
  VOXLINK_ASSIGN_OR_RETURN(const ComputeProgram* secondary,
                           program(settings, Pass::kEffectsSecondary));
  VOXLINK_ASSIGN_OR_RETURN(const ComputeProgram* resolve, program(settings, Pass::kEffectsResolve));
  const uint32_t w = settings.width, h = settings.height;
  if (uint64_t(w) * h > kMaxEffectsPixels)
    return makeError(ErrorCode::kInvalidArgument, name(), ": the ray-traced mode renders at most ",
                     kMaxEffectsPixels, " pixels (8192x8192); ", w, "x", h, " is larger");
  VOXLINK_RETURN_IF_ERROR(target.resize(w, h));
  VOXLINK_RETURN_IF_ERROR(effects_.resize(w, h));
  effectsStats_ = {};
  const GLbitfield barrier =
      GL_SHADER_STORAGE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT;
  auto start = [&](const ComputeProgram& p) {
    p.use();
    setFrameUniforms(p, camera, settings, w, h);
    setEffectsUniforms(p, camera, settings);
    bindTables(p);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kAccumBinding, effects_.accum().buffer.id());
    glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, effects_.counters());
    effects_.clearCounters();
  };

  // Primary rays: every pixel's accumulator is written, spawned rays go to buffer 0.
  start(*primary);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRaysOutBinding, effects_.rays(0).buffer.id());
  glDispatchCompute((w + 7) / 8, (h + 7) / 8, 1);
  effectsStats_.passes = 1;
  // A ray generation crosses fewer occupied bricks than the grid has along its three axes, so
  // each of the maxBounces + 1 generations needs at most that / stepsPerPass + 1 passes; rays left
  // after that many (none, unless something is wrong) are counted as dropped.
  const auto& dims = geometry_.dims;
  const int steps = std::max(1, settings.effects.stepsPerPass);
  const int64_t maxPasses = int64_t(settings.effects.maxBounces + 1) *
                            (int64_t(dims[0]) + dims[1] + dims[2] + 3 + steps) / steps;
  for (int pass = 1;; ++pass) {
    glMemoryBarrier(barrier);
    const auto [spawned, dropped] = effects_.readCounters();
    effectsStats_.droppedRays += dropped;
    const uint32_t count = std::min(spawned, effects_.rayCapacity());
    if (count == 0) break;
    if (pass >= maxPasses) {
      effectsStats_.droppedRays += count;
      break;
    }
    start(*secondary);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRaysInBinding,
                     effects_.rays((pass + 1) % 2).buffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRaysOutBinding,
                     effects_.rays(pass % 2).buffer.id());
    glUniform1ui(secondary->uniform("uRayCount"), count);
    glDispatchCompute((count + 63) / 64, 1, 1);
    effectsStats_.passes += 1;
    effectsStats_.secondaryRays += count;
  }
  glMemoryBarrier(barrier);
  resolve->use();
  glUniform2ui(resolve->uniform("uImageSize"), w, h);
  const auto& bg = settings.background;
  glUniform3f(resolve->uniform("uBackground"), float(bg[0]), float(bg[1]), float(bg[2]));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kAccumBinding, effects_.accum().buffer.id());
  glBindImageTexture(0, target.texture(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute((w + 7) / 8, (h + 7) / 8, 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                  GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  if (const GLenum e = glGetError(); e != GL_NO_ERROR)
    return makeError(ErrorCode::kUnsupported, "render (", name(), " renderer): GL error 0x",
                     std::hex, e, " while ray tracing effects");
  return Status::ok();
}

}  // namespace voxlink::render::gl
