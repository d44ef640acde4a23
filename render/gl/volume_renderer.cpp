// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/detail/volume_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "format/gradient_codec.h"

namespace voxlink::render::gl {

using tf::buildTfTable;

namespace {

// sin/cos tables taken from format::decodeGradient, so the shader decodes bit-identically:
// entries [0, 255) are (sin theta, cos theta), [255, 511) are (cos phi, sin phi).
std::vector<float> gradientTable() {
  std::vector<float> t;
  for (int theta = 0; theta <= format::kPolarSteps; ++theta) {
    const auto v = format::decodeGradient(uint16_t(theta << 8));  // phi = 0: (sin, 0, cos)
    t.push_back(v[0]);
    t.push_back(v[2]);
  }
  for (int phi = 0; phi < format::kAzimuthSteps; ++phi) {
    const auto v = format::decodeGradient(uint16_t((format::kPolarSteps / 2) << 8 | phi));
    t.push_back(v[0]);  // sin(pi/2) = 1: (cos phi, sin phi, 0)
    t.push_back(v[1]);
  }
  return t;
}

}  // namespace

VolumeGeometry VolumeGeometry::of(const format::FileHeader& h) {
  VolumeGeometry g;
  for (int a = 0; a < 3; ++a) {
    g.dims[a] = h.dims[a];
    g.spacing[a] = h.spacing[a];
    g.origin[a] = h.origin[a];
  }
  g.valueType = static_cast<StoredType>(h.valueType);
  g.valueScale = h.valueScale;
  g.valueOffset = h.valueOffset;
  if (h.surfaceMode == uint32_t(format::SurfaceMode::kPlanes))
    g.surfaceOffsetVoxels = render::kListSurfaceOffset;
  if (h.surfaceMode == uint32_t(format::SurfaceMode::kTriangles))
    g.surfaceOffsetVoxels = render::kTriangleSurfaceOffset;
  return g;
}

Box VolumeGeometry::worldBox() const {
  Box b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = origin[a] - 0.5 * spacing[a];
    b.hi[a] = origin[a] + (double(dims[a]) - 0.5) * spacing[a];
  }
  return b;
}

GLuint tfTextureUnit() {
  GLint units = 0;
  glGetIntegerv(GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS, &units);
  return GLuint(std::max(units, 16) - 1);  // GL 4.3 guarantees 16
}

double VolumeGeometry::minSpacing() const { return std::min({spacing[0], spacing[1], spacing[2]}); }

VolumeRenderer::VolumeRenderer(const VolumeGeometry& geometry) : geometry_(geometry) {
  const std::vector<float> table = gradientTable();
  gradientTable_ = createStorageBuffer(table.data(), table.size() * sizeof(float));
  tf::TransferFunction identity;
  identity.opacity = {{0.0, 0.0}};
  identity.color = {{0.0, {1, 1, 1}}};
  setTransferFunction(identity);
}

void VolumeRenderer::setTransferFunction(const tf::TransferFunction& tf) {
  tf_ = tf;
  ++tfGeneration_;  // the shadow cache's codes were walked through the old opacities
  table_ = buildTfTable(tf, geometry_.valueType, geometry_.valueScale, geometry_.valueOffset);
  // A texture buffer may not be empty.
  std::vector<float> texels = table_.texels;
  if (slicesTf())  // the entries of the values the file holds (transfer_function.glsl)
    texels.assign(
        table_.texels.begin() + 4 * size_t(geometry_.firstValueBits),
        table_.texels.begin() + 4 * size_t(geometry_.firstValueBits + geometry_.valueBitsCount));
  if (texels.empty()) texels.assign(4, 0.0f);
  if (premultipliedTf()) {
    // 8-bit files: (colour * opacity, opacity) of value i at texel 256 + i as well, so a
    // trilinear corner skips 3 multiplies (transfer_function.glsl). Float products, as the
    // shader formed them: images stay bit-identical. And its optical depth at 512 + i.
    texels.resize(3 * kU8TfEntries * 4, 0.0f);
    for (size_t i = 0; i < kU8TfEntries; ++i) {
      const float* c = &texels[4 * i];
      float* p = &texels[4 * (kU8TfEntries + i)];
      p[0] = c[0] * c[3];
      p[1] = c[1] * c[3];
      p[2] = c[2] * c[3];
      p[3] = c[3];
      // Texel 512 + i: -log2(1 - opacity) for shadow walks (unitOpticalDepth), in double.
      texels[4 * (2 * kU8TfEntries + i)] =
          float(-std::log2(1.0 - std::min(double(c[3]), render::kMaxUnitAlpha)));
    }
  }
  tfBuffer_ = createStorageBuffer(texels.data(), texels.size() * sizeof(float));
  tfBytes_ = texels.size() * sizeof(float);
  // The same buffer as RGBA texels: on llvmpipe a texel fetch (a gather) costs about 35
  // instructions per SIMD vector, a storage-buffer read (a loop over the lanes) about 90, and a
  // trilinear sample reads the TF for 8 corners (docs/rendering-benchmark.md).
  tfTexels_ = createTexture(GL_TEXTURE_BUFFER);
  glTextureBuffer(tfTexels_.id(), GL_RGBA32F, tfBuffer_.buffer.id());
}

bool VolumeRenderer::slicesTf() const {
  return geometry_.valueBitsCount > 0 && table_.kind == tf::TfTable::Kind::kIndexed &&
         !premultipliedTf();
}

bool VolumeRenderer::premultipliedTf() const {
  return geometry_.valueType == StoredType::kU8 && table_.kind == tf::TfTable::Kind::kIndexed;
}

Result<const ComputeProgram*> VolumeRenderer::program(const RenderSettings& s, Pass pass) {
  const bool fill = pass == Pass::kShadowFill || pass == Pass::kShadowFillMarked;
  const bool mark = pass == Pass::kShadowMark;  // the plain frame's shader, marking
  const bool effects = pass != Pass::kPlain && !fill && !mark;
  const bool shadows = s.shading.enabled && (s.shading.shadows || (effects && s.effects.shadows));
  // pow() specialised away where the settings allow (shading.glsl): a half-voxel step, an
  // integer specular exponent.
  const bool halfVoxelStep = s.stepVoxels == 0.5;
  const double e = s.shading.shininess;
  const int shininess = e >= 1 && e <= 127 && e == std::floor(e) ? int(e) : 0;
  // The ray-traced mode casts its own shadow rays; the cache serves the plain frame's.
  const bool shadowCache = shadows && (pass == Pass::kPlain || fill || mark) && cachesShadows(s);
  const auto key = std::make_tuple(int(s.sampling), shadows, int(pass), int(s.lights.size()),
                                   halfVoxelStep, shininess, shadowCache);
  if (auto it = programs_.find(key); it != programs_.end()) return &it->second;
  if (pass == Pass::kEffectsResolve) {
    VOXLINK_ASSIGN_OR_RETURN(
        ComputeProgram p,
        ComputeProgram::build("effects_resolve.comp.glsl",
                              {{"VXL_ACCUM_BINDING", std::to_string(kAccumBinding)}}, {}));
    return &programs_.emplace(key, std::move(p)).first->second;
  }
  std::vector<ShaderDefine> defines = dataDefines();
  defines.push_back({"VXL_EFFECTS", effects ? "1" : "0"});
  if (effects) {
    defines.push_back({"VXL_EFFECTS_PRIMARY", pass == Pass::kEffectsPrimary ? "1" : "0"});
    defines.push_back({"VXL_MAX_LIGHTS", std::to_string(kMaxLights)});
    defines.push_back({"VXL_RAYS_IN_BINDING", std::to_string(kRaysInBinding)});
    defines.push_back({"VXL_RAYS_OUT_BINDING", std::to_string(kRaysOutBinding)});
    defines.push_back({"VXL_ACCUM_BINDING", std::to_string(kAccumBinding)});
  }
  defines.push_back({"VXL_TRILINEAR", s.sampling == Sampling::kTrilinear ? "1" : "0"});
  defines.push_back({"VXL_HALF_VOXEL_STEP", halfVoxelStep ? "1" : "0"});
  defines.push_back({"VXL_SHININESS", std::to_string(shininess)});
  defines.push_back({"VXL_SHADOWS", shadows ? "1" : "0"});
  defines.push_back({"VXL_SHADOW_CACHE", shadowCache ? "1" : "0"});
  defines.push_back({"VXL_SHADOW_MARK", mark ? "1" : "0"});
  defines.push_back({"VXL_SHADOW_MARKED", pass == Pass::kShadowFillMarked ? "1" : "0"});
  defines.push_back({"VXL_RETRACE_BINDING", std::to_string(kRetraceBinding)});
  defines.push_back({"VXL_TF_BINDING", std::to_string(kTfBinding)});
  defines.push_back({"VXL_TF_UNIT", std::to_string(tfTextureUnit())});
  defines.push_back({"VXL_TF_PREMULTIPLIED", premultipliedTf() ? "1" : "0"});
  defines.push_back({"VXL_TF_FIRST", std::to_string(slicesTf() ? geometry_.firstValueBits : 0u)});
  defines.push_back({"VXL_GRADIENT_TABLE_BINDING", std::to_string(kGradientTableBinding)});
  defines.push_back({"VXL_TF_BREAKPOINTS", geometry_.valueType == StoredType::kF32 ? "1" : "0"});
  const std::string shader = fill ? shadowFillShader() : effects ? effectsShader() : mainShader();
  VOXLINK_ASSIGN_OR_RETURN(ComputeProgram p,
                           ComputeProgram::build(shader, defines, generatedFiles()));
  return &programs_.emplace(key, std::move(p)).first->second;
}

void VolumeRenderer::bindTables(const ComputeProgram& p) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTfBinding, tfBuffer_.buffer.id());
  glBindTextureUnit(tfTextureUnit(), tfTexels_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGradientTableBinding, gradientTable_.buffer.id());
  bindData(p);
}

namespace {

// The frame's directional light in world space (it follows the camera), as the shaders get it.
glm::vec3 worldToLight(const Camera& camera, const RenderSettings& s) {
  const auto& l = s.shading.lightDirection;
  return glm::vec3(glm::normalize(camera.toWorld(glm::normalize(glm::dvec3(l[0], l[1], l[2])))));
}

}  // namespace

bool VolumeRenderer::marks(const RenderSettings& s) const {
  if (marking_ != ShadowMarking::kAuto) return marking_ == ShadowMarking::kOn;
  if (const char* env = std::getenv("VOXLINK_SHADOW_MARK"); env && (*env == '0' || *env == '1'))
    return *env == '1';
  return marksByDefault(s);
}

VolumeRenderer::MarkedView VolumeRenderer::markedView(const Camera& camera, const RenderSettings& s,
                                                      uint32_t width, uint32_t height) const {
  const glm::dvec2 half = camera.planeHalfExtent(width, height);
  MarkedView v;
  v.eye = glm::vec3(camera.eye());
  v.forward = glm::vec3(-camera.back());
  v.right = glm::vec3(camera.right() * half.x);
  v.up = glm::vec3(camera.up() * half.y);
  v.width = width;
  v.height = height;
  v.sampling = int(s.sampling);
  v.step = float(s.stepVoxels * geometry_.minSpacing());
  v.stopTransmittance = float(1.0 - s.terminationAlpha);
  return v;
}

void VolumeRenderer::setFrameUniforms(const ComputeProgram& p, const Camera& camera,
                                      const RenderSettings& s, uint32_t width,
                                      uint32_t height) const {
  auto vec3 = [&](const char* name, const glm::dvec3& v) {
    glUniform3f(p.uniform(name), float(v.x), float(v.y), float(v.z));
  };
  auto fvec3 = [&](const char* name, const glm::vec3& v) {
    glUniform3f(p.uniform(name), v.x, v.y, v.z);
  };
  const MarkedView view = markedView(camera, s, width, height);
  fvec3("uEyeWorld", view.eye);
  fvec3("uCamForward", view.forward);
  fvec3("uCamRight", view.right);
  fvec3("uCamUp", view.up);
  glUniform2ui(p.uniform("uImageSize"), width, height);
  const auto& g = geometry_;
  vec3("uVolumeOrigin", {g.origin[0], g.origin[1], g.origin[2]});
  vec3("uVolumeSpacing", {g.spacing[0], g.spacing[1], g.spacing[2]});
  glUniform3i(p.uniform("uDims"), GLint(g.dims[0]), GLint(g.dims[1]), GLint(g.dims[2]));
  const double unit = g.minSpacing();
  glUniform1f(p.uniform("uUnit"), float(unit));
  glUniform1f(p.uniform("uStep"), view.step);
  const glm::vec3 toLight = worldToLight(camera, s);
  glUniform3f(p.uniform("uToLight"), toLight.x, toLight.y, toLight.z);
  glUniform4f(p.uniform("uPhong"), float(s.shading.ambient), float(s.shading.diffuse),
              float(s.shading.specular), float(s.shading.shininess));
  glUniform1i(p.uniform("uShadingEnabled"), s.shading.enabled ? 1 : 0);
  glUniform1f(p.uniform("uStopTransmittance"), view.stopTransmittance);
  glUniform1f(p.uniform("uShadowStop"), float(s.shadowTerminationTransmittance));
  vec3("uBackground", {s.background[0], s.background[1], s.background[2]});
  glUniform1i(p.uniform("uTfEntries"), GLint(table_.entries));
  glUniform1f(p.uniform("uValueScale"), float(g.valueScale));
  glUniform1f(p.uniform("uValueOffset"), float(g.valueOffset));
}

Status VolumeRenderer::render(const Camera& camera, const RenderSettings& settings,
                              RenderTarget& target) {
  VOXLINK_RETURN_IF_ERROR(checkSettings(settings, name()));
  VOXLINK_RETURN_IF_ERROR(checkSupported(settings));
  if (settings.effects.any()) return renderEffects(camera, settings, target);
  VOXLINK_ASSIGN_OR_RETURN(const ComputeProgram* p, program(settings));
  VOXLINK_RETURN_IF_ERROR(target.resize(settings.width, settings.height));
  // The frame's program, or the marking frame's (the same traversal), writing into the target.
  auto useForFrame = [&](const ComputeProgram& program) {
    program.use();
    setFrameUniforms(program, camera, settings, settings.width, settings.height);
    bindTables(program);
    glBindImageTexture(0, target.texture(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  };
  const bool cached =
      settings.shading.enabled && settings.shading.shadows && cachesShadows(settings);
  if (cached) {
    const bool marked = marks(settings);
    ShadowFill wanted{worldToLight(camera, settings),
                      float(settings.shadowTerminationTransmittance), tfGeneration_, marked};
    if (marked) wanted.view = markedView(camera, settings, settings.width, settings.height);
    // Codes of every visible voxel (an unmarked fill) serve any view, marked ones their own.
    const bool reuse = filledFor_ && filledFor_->toLight == wanted.toLight &&
                       filledFor_->stop == wanted.stop &&
                       filledFor_->tfGeneration == wanted.tfGeneration &&
                       (!filledFor_->marked || *filledFor_ == wanted);
    const bool refill = !reuse;
    if (reuse) wanted = *filledFor_;
    filledFor_.reset();  // until the fill below is queued
    VOXLINK_RETURN_IF_ERROR(beginShadowCache(refill, refill && marked));
    if (refill && marked) {
      // The frame's traversal, marking the centres it reads (its image is drawn over below).
      VOXLINK_ASSIGN_OR_RETURN(const ComputeProgram* mark, program(settings, Pass::kShadowMark));
      useForFrame(*mark);
      glDispatchCompute((settings.width + 7) / 8, (settings.height + 7) / 8, 1);
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
      ++shadowMarks_;
    }
    if (refill) {
      VOXLINK_ASSIGN_OR_RETURN(
          const ComputeProgram* fill,
          program(settings, marked ? Pass::kShadowFillMarked : Pass::kShadowFill));
      fill->use();
      setFrameUniforms(*fill, camera, settings, settings.width, settings.height);
      bindTables(*fill);
      fillShadowCache(*fill);
      ++shadowFills_;
    }
    filledFor_ = wanted;
  }
  useForFrame(*p);
  // Only shadow rays make rays long enough to reach a driver's loop cap (loop_limit_retrace.h);
  // a frame that reads filled shadow codes walks none (the fill pass walks one per invocation).
  const bool shadows = settings.shading.enabled && settings.shading.shadows && !cached;
  if (shadows) retrace_.begin(*p, settings.width, settings.height);
  glDispatchCompute((settings.width + 7) / 8, (settings.height + 7) / 8, 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                  GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  lastRetraced_ = 0;
  if (shadows) {
    VOXLINK_ASSIGN_OR_RETURN(lastRetraced_, retrace_.finish(*p, name()));
  }
  if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
    filledFor_.reset();  // the fill may not have run
    return makeError(ErrorCode::kUnsupported, "render (", name(), " renderer): GL error 0x",
                     std::hex, e, " while rendering");
  }
  return Status::ok();
}

}  // namespace voxlink::render::gl
