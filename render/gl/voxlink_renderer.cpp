// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/voxlink_renderer.h"

#include <algorithm>
#include <cstring>

#include "render/brick_lookup.h"
#include "render/gl/detail/volume_renderer.h"

namespace voxlink::render::gl {

std::vector<ShaderDefine> voxlinkDefines(const format::FileHeader& h) {
  return {{"VXL_N", std::to_string(h.brickSize)},
          {"VXL_AXIS", std::to_string(h.predominantAxis)},
          {"VXL_VALUE_BYTES", std::to_string(storedSize(static_cast<StoredType>(h.valueType)))},
          {"VXL_SCENE", h.versionMajor == format::kVersionMajorScene ? "1" : "0"},
          {"VXL_SPHERES", h.sphereCount > 0 ? "1" : "0"},
          {"VXL_SURFACE_MODE",
           std::to_string(h.versionMajor == format::kVersionMajorScene ? h.surfaceMode : 0u)}};
}

namespace {

// The header's geometry, with the stored values a 16-bit file holds: its TF table then has
// their entries only (the carp CT, a 0.71 MB file, had 1 MiB of TF texels for 65,536 values).
VolumeGeometry geometryOf(const format::VoxLinkFile& file) {
  VolumeGeometry g = VolumeGeometry::of(file.header());
  const uint64_t slots = format::sampleSlots(file.header());
  if (storedSize(file.valueType()) != 2 || slots == 0) return g;
  uint16_t lo = 0xFFFF, hi = 0;
  for (uint64_t i = 0; i < slots; ++i) {
    uint16_t bits;
    std::memcpy(&bits, file.valueBytes() + 2 * i, 2);
    lo = std::min(lo, bits);
    hi = std::max(hi, bits);
  }
  g.firstValueBits = lo;
  g.valueBitsCount = uint32_t(hi) - lo + 1u;
  return g;
}

}  // namespace

Result<std::unique_ptr<VoxLinkRenderer>> VoxLinkRenderer::create(
    const format::VoxLinkFile& file, const SectionBufferOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(SectionBuffers sections, SectionBuffers::upload(file, options));
  return std::unique_ptr<VoxLinkRenderer>(new VoxLinkRenderer(file, std::move(sections)));
}

VoxLinkRenderer::VoxLinkRenderer(const format::VoxLinkFile& file, SectionBuffers sections)
    : VolumeRenderer(geometryOf(file)),
      sections_(std::move(sections)),
      header_(file.header()),
      brickCells_(file.isScene() ? std::vector<uint32_t>() : occupiedBrickCells(file)) {}

Status VoxLinkRenderer::checkSupported(const RenderSettings& settings) const {
  if (header_.versionMajor == format::kVersionMajorScene && settings.sampling != Sampling::kVoxel)
    return makeError(ErrorCode::kUnsupported,
                     "scenes (files with geometry) render with voxel sampling; ",
                     samplingName(settings.sampling), " sampling is for volume files");
  return Status::ok();
}

// The shadow cache reads through the texture unit below the TF table's (volume_renderer.h).
GLuint shadowCacheUnit() { return tfTextureUnit() - 1; }

std::vector<ShaderDefine> VoxLinkRenderer::dataDefines() const {
  std::vector<ShaderDefine> defines = voxlinkDefines(header_);
  defines.push_back({"VXL_SHADOW_CACHE_UNIT", std::to_string(shadowCacheUnit())});
  defines.push_back({"VXL_SHADOW_CACHE_IMAGE", std::to_string(kShadowCacheImage)});
  defines.push_back({"VXL_SHADOW_MARK_IMAGE", std::to_string(kShadowMarkImage)});
  defines.push_back({"VXL_BRICK_CELLS_BINDING", std::to_string(kBrickCellsBinding)});
  return defines;
}

// Volume files: a scene's shadow rays also cross its geometry, and stay per sample.
bool VoxLinkRenderer::cachesShadows(const RenderSettings& settings) const {
  return settings.shading.shadowRays == ShadowRays::kPerVoxel &&
         header_.versionMajor != format::kVersionMajorScene;
}

// A frame reads 54-95 % of the visible centres at 1000x1000 and as few as 29 % where the
// pixels are fewer than the voxel columns on screen (docs/shadows.md, "What a frame reaches"):
// a marking frame pays where the pixels are few against the slots the fill would walk, and in
// voxel sampling only (a trilinear frame marks 8 corners a cell and reads 55-95 %: measured
// slower on all three CT files at 512x512 and on two of three at 256x256).
bool VoxLinkRenderer::marksByDefault(const RenderSettings& settings) const {
  return settings.sampling == Sampling::kVoxel &&
         2 * uint64_t(settings.width) * settings.height < sections_.voxelSlots();
}

Status VoxLinkRenderer::beginShadowCache(bool refill, bool clearMarks) {
  if (!shadowCache_) {
    if (sections_.endUnit() > shadowCacheUnit())
      return makeError(ErrorCode::kTooLarge,
                       "shadow cache: the file's sections take texture units "
                       "up to ",
                       sections_.endUnit() - 1, ", the cache's unit ", shadowCacheUnit(),
                       " among them; use --shadow-rays per-sample");
    VOXLINK_ASSIGN_OR_RETURN(
        ShadowCacheBuffer cache,
        ShadowCacheBuffer::create(sections_.voxelSlots(), shadowCacheUnit(), brickCells_));
    shadowCache_ = std::move(cache);
  }
  if (refill) shadowCache_->clear();
  if (clearMarks) shadowCache_->clearMarks();
  shadowCache_->bind();
  return Status::ok();
}

void VoxLinkRenderer::fillShadowCache(const ComputeProgram& program) const {
  // Depth n is a row's apron copy, where row words have one (shadow_fill.comp.glsl).
  shadowCache_->fill(program.uniform("uOccupiedBricks"), program.uniform("uDepths"),
                     header_.brickSize + (sections_.rowApron() ? 1 : 0));
}

std::map<std::string, std::string> VoxLinkRenderer::generatedFiles() const {
  return {{"voxlink_sections.glsl", sections_.glsl()}};
}

void VoxLinkRenderer::bindData(const ComputeProgram& program) const {
  sections_.bind();
  glUniform3i(program.uniform("uBrickGrid"), GLint(header_.brickGrid[0]),
              GLint(header_.brickGrid[1]), GLint(header_.brickGrid[2]));
}

}  // namespace voxlink::render::gl
