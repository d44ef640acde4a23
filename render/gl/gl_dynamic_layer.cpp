// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/gl_dynamic_layer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/voxel_grid.h"
#include "render/gl/detail/gl_objects.h"
#include "render/gl/shader_program.h"

namespace voxlink::render::gl {
namespace {

constexpr GLuint kEmpty = 0xffffffffu;
constexpr uint64_t kPoolVoxelBytes = 16;  // ivec4, shaders/dynamic_layer_build.comp.glsl
constexpr double kFixedPoint = 4096;      // units per voxel^2 of area x unit normal
// Where the raster and compute stages read pool buffer i, and kept buffer i
// (shaders/dynamic_layer*.glsl).
constexpr GLuint kPoolBindings[GlDynamicLayer::kMaxPoolBuffers] = {6, 14, 15, 16};
constexpr GLuint kKeptBindings[GlDynamicLayer::kMaxPoolBuffers] = {13, 17, 18, 19};

GLint getInteger(GLenum name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

GlBuffer storage(uint64_t bytes, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT) {
  GlBuffer b = createBuffer();
  glNamedBufferStorage(b.id(), GLsizeiptr(std::max<uint64_t>(bytes, 16)), nullptr, flags);
  return b;
}

}  // namespace

struct GlDynamicLayer::State {
  std::array<uint32_t, 3> dims{}, brickGrid{};
  uint32_t brickSize = 8, edge = 0;
  uint64_t brickCapacity = 0, slotsPerBuffer = 0;
  size_t vertexFloats = 0, triangleIndices = 0;
  GLuint raster = 0, vertexArray = 0;
  ComputeProgram build, keepCopy;
  GlFramebuffer framebuffer;
  GlBuffer dispatchSize, positions, indices, order, contributions, brickMap, counters, slotKeys,
      usedSlots;
  std::vector<GlBuffer> pool;  // slot s in pool[s / slotsPerBuffer]
  // What keep() saved: the brick map, hash keys, used-slot list and counters whole, and the
  // used slots' bricks packed (keptBricks of room for keptRoom).
  GlBuffer keptBrickMap, keptSlotKeys, keptUsedSlots, keptCounters;
  std::vector<GlBuffer> keptPool;  // kept brick k in keptPool[k / slotsPerBuffer]
  uint64_t keptBricks = 0, keptRoom = 0;
  bool kept = false;
  ~State() {
    if (raster) glDeleteProgram(raster);
    if (vertexArray) glDeleteVertexArrays(1, &vertexArray);
  }
};

GlDynamicLayer::GlDynamicLayer(std::unique_ptr<State> state) : s_(std::move(state)) {}
GlDynamicLayer::GlDynamicLayer(GlDynamicLayer&&) noexcept = default;
GlDynamicLayer& GlDynamicLayer::operator=(GlDynamicLayer&&) noexcept = default;
GlDynamicLayer::~GlDynamicLayer() = default;
bool GlDynamicLayer::hasKept() const { return s_->kept; }
void GlDynamicLayer::forgetKept() { s_->kept = false; }
GLuint GlDynamicLayer::brickMap() const { return s_->brickMap.id(); }
uint32_t GlDynamicLayer::poolBuffers() const { return uint32_t(s_->pool.size()); }
GLuint GlDynamicLayer::poolBuffer(uint32_t i) const { return s_->pool.at(i).id(); }
uint64_t GlDynamicLayer::slotsPerPoolBuffer() const { return s_->slotsPerBuffer; }

std::vector<ShaderDefine> GlDynamicLayer::poolDefines() const {
  return {{"VXL_DYN_POOLS", std::to_string(s_->pool.size())},
          {"VXL_DYN_POOL_SLOTS", std::to_string(s_->slotsPerBuffer) + "u"}};
}

// Binds the pool's buffers, and with `kept` the kept ones, where the compute and raster stages
// read them; a kept buffer that does not exist (fewer bricks kept) is bound to the first.
static void bindPool(const std::vector<GlBuffer>& pool, const std::vector<GlBuffer>* kept) {
  for (size_t i = 0; i < pool.size(); ++i) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPoolBindings[i], pool[i].id());
    if (kept)
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kKeptBindings[i],
                       (*kept)[i < kept->size() ? i : 0].id());
  }
}
uint32_t GlDynamicLayer::brickSize() const { return s_->brickSize; }

uint64_t GlDynamicLayer::gpuBytes() const {
  const uint64_t bricks = uint64_t(s_->brickGrid[0]) * s_->brickGrid[1] * s_->brickGrid[2];
  const uint64_t n3 = uint64_t(s_->brickSize) * s_->brickSize * s_->brickSize;
  const uint64_t kept = s_->keptBrickMap ? bricks * 4 + s_->brickCapacity * 8 + 8 : 0;
  return bricks * 4 + s_->brickCapacity * (n3 * kPoolVoxelBytes + 8) + kept +
         s_->keptRoom * n3 * kPoolVoxelBytes;
}

uint64_t dynamicBrickBound(const std::array<double, 3>& extent, uint32_t brickSize,
                           const std::array<uint32_t, 3>& dims) {
  uint64_t bricks = 1;
  for (int a = 0; a < 3; ++a) {
    const uint64_t grid = (uint64_t(dims[a]) + brickSize - 1) / brickSize;
    bricks *= std::min<uint64_t>(grid, uint64_t(std::ceil(extent[a] / brickSize)) + 1);
  }
  return bricks;
}

Result<GlDynamicLayer> GlDynamicLayer::create(const std::array<uint32_t, 3>& dims,
                                              uint32_t brickSize, uint64_t brickCapacity,
                                              uint64_t bytesPerBuffer) {
  auto s = std::make_unique<State>();
  s->dims = dims;
  s->brickSize = brickSize;
  s->edge = std::max({dims[0], dims[1], dims[2]});
  for (int a = 0; a < 3; ++a) s->brickGrid[a] = (dims[a] + brickSize - 1) / brickSize;
  const uint64_t maxBlock = uint64_t(std::max(getInteger(GL_MAX_SHADER_STORAGE_BLOCK_SIZE), 0));
  const uint64_t n3 = uint64_t(brickSize) * brickSize * brickSize;
  // One binding holds at most GL_MAX_SHADER_STORAGE_BLOCK_SIZE bytes (128 MiB on llvmpipe), not
  // what memory allows: the pool is split over up to kMaxPoolBuffers buffers. The bound from the
  // moving objects' boxes can exceed even those where the surface itself would fit: the pool
  // takes what fits, and an update that needs more is an error (checkLastUpdate), never a frame
  // with missing bricks.
  const uint64_t bufferBytes = bytesPerBuffer ? std::min(bytesPerBuffer, maxBlock) : maxBlock;
  const uint64_t brickBytes = n3 * kPoolVoxelBytes;
  s->slotsPerBuffer = bufferBytes / brickBytes;
  if (s->slotsPerBuffer == 0)
    return makeError(ErrorCode::kTooLarge, "dynamic layer: a brick of ", brickBytes,
                     " bytes exceeds a storage buffer's ", bufferBytes,
                     " (GL_MAX_SHADER_STORAGE_BLOCK_SIZE)");
  brickCapacity =
      std::max<uint64_t>(1, std::min(brickCapacity, uint64_t(kMaxPoolBuffers) * s->slotsPerBuffer));
  s->brickCapacity = brickCapacity;
  if (int64_t(s->edge) > getInteger(GL_MAX_FRAMEBUFFER_WIDTH))
    return makeError(ErrorCode::kTooLarge, "dynamic layer: grid edge ", s->edge,
                     " exceeds the largest framebuffer");
  // VXL_DYN_N: the voxelizer's stages write the layer; a constant brick edge spares divisions.
  const uint64_t buffers = (brickCapacity + s->slotsPerBuffer - 1) / s->slotsPerBuffer;
  // One buffer: the slots of a buffer are the capacity (the shaders' split is compiled out).
  if (buffers == 1) s->slotsPerBuffer = brickCapacity;
  for (uint64_t b = 0; b < buffers; ++b)
    s->pool.push_back(storage(
        std::min(s->slotsPerBuffer, brickCapacity - b * s->slotsPerBuffer) * brickBytes, 0));
  const std::vector<ShaderDefine> poolDefines = {
      {"VXL_DYN_POOLS", std::to_string(buffers)},
      {"VXL_DYN_POOL_SLOTS", std::to_string(s->slotsPerBuffer) + "u"}};
  std::vector<ShaderDefine> layerDefines = {{"VXL_DYN_N", std::to_string(brickSize)}};
  layerDefines.insert(layerDefines.end(), poolDefines.begin(), poolDefines.end());
  std::vector<ShaderDefine> computeDefines = {{"VXL_N", std::to_string(brickSize)}};
  computeDefines.insert(computeDefines.end(), poolDefines.begin(), poolDefines.end());
  VOXLINK_ASSIGN_OR_RETURN(
      GLuint vertex, compileShaderStage(GL_VERTEX_SHADER, "gl_voxelize.vert.glsl", layerDefines));
  auto fragment = compileShaderStage(GL_FRAGMENT_SHADER, "gl_voxelize.frag.glsl", layerDefines);
  if (!fragment) {
    glDeleteShader(vertex);
    return fragment.error();
  }
  VOXLINK_ASSIGN_OR_RETURN(s->raster, linkProgram({vertex, *fragment}, "gl_voxelize"));
  VOXLINK_ASSIGN_OR_RETURN(s->build,
                           ComputeProgram::build("dynamic_layer_build.comp.glsl", computeDefines));
  VOXLINK_ASSIGN_OR_RETURN(s->keepCopy,
                           ComputeProgram::build("dynamic_layer_keep.comp.glsl", computeDefines));
  glCreateVertexArrays(1, &s->vertexArray);
  GLuint fb = 0;
  glCreateFramebuffers(1, &fb);
  s->framebuffer = GlFramebuffer(fb);
  glNamedFramebufferParameteri(fb, GL_FRAMEBUFFER_DEFAULT_WIDTH, GLint(s->edge));
  glNamedFramebufferParameteri(fb, GL_FRAMEBUFFER_DEFAULT_HEIGHT, GLint(s->edge));
  s->dispatchSize = storage(12);
  s->brickMap = storage(uint64_t(s->brickGrid[0]) * s->brickGrid[1] * s->brickGrid[2] * 4);
  s->counters = storage(8);
  s->slotKeys = storage(brickCapacity * 4);
  s->usedSlots = storage(brickCapacity * 4);
  // An empty layer until the first update; from then on each update zeroes what the last used.
  const GLuint empty = kEmpty, zero = 0;
  glClearNamedBufferData(s->brickMap.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
  for (const GlBuffer* b : {&s->counters, &s->slotKeys, &s->dispatchSize})
    glClearNamedBufferData(b->id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  for (const GlBuffer& b : s->pool)
    glClearNamedBufferData(b.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  if (GLenum e = glGetError(); e != GL_NO_ERROR)
    return makeError(ErrorCode::kTooLarge, "dynamic layer: GL error 0x", std::hex, e,
                     " allocating ", (brickCapacity * brickBytes) >> 20, " MiB of brick pool in ",
                     buffers, " buffers");
  return GlDynamicLayer(std::move(s));
}

Status GlDynamicLayer::update(const std::vector<float>& positions,
                              const std::vector<uint32_t>& triangles,
                              const std::vector<uint32_t>& triangleMaterials, bool onKept) {
  if (onKept && !s_->kept)
    return makeError(ErrorCode::kInvalidArgument,
                     "dynamic layer: an update on a kept layer "
                     "before keep()");
  if (triangleMaterials.size() * 3 != triangles.size())
    return makeError(ErrorCode::kSizeMismatch, "dynamic layer: ", triangleMaterials.size(),
                     " triangle materials for ", triangles.size() / 3, " triangles");
  State& s = *s_;
  // Triangles binned by dominant axis (the voxelizer's swizzle), zero-area ones left out; per
  // triangle its contribution to a voxel (shaders/dynamic_layer_build.comp.glsl: area x unit
  // normal in fixed point, the area clamped to [1/256, 256] voxel^2 so that a sum of 2^13 fits an
  // int, and material + 1); the voxel box of the vertices for the ray tracer.
  std::array<std::vector<uint32_t>, 3> byAxis;
  std::vector<std::array<int32_t, 4>> contributions(triangleMaterials.size(), {0, 0, 0, 0});
  const size_t vertexCount = positions.size() / 3;
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const float* c[3];
    for (int k = 0; k < 3; ++k) {
      if (triangles[t + size_t(k)] >= vertexCount)
        return makeError(ErrorCode::kInvalidArgument, "dynamic layer: triangle ", t / 3,
                         ": vertex index out of range");
      c[k] = &positions[3 * size_t(triangles[t + size_t(k)])];
    }
    const double e1[3] = {c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2]};
    const double e2[3] = {c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2]};
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    if (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0) continue;
    const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double scale = 0.5 / area * std::clamp(area, 1.0 / 256, 256.0) * kFixedPoint;
    auto& c4 = contributions[t / 3];
    for (int a = 0; a < 3; ++a) c4[size_t(a)] = int32_t(std::lround(n[a] * scale));
    c4[3] = int32_t(triangleMaterials[t / 3]) + 1;
    int w = 0;
    if (std::abs(n[1]) > std::abs(n[w])) w = 1;
    if (std::abs(n[2]) > std::abs(n[w])) w = 2;
    byAxis[size_t(w)].push_back(uint32_t(t / 3));
  }
  std::array<float, 3> lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  for (size_t v = 0; v < vertexCount; ++v)
    for (int a = 0; a < 3; ++a) {
      lo[size_t(a)] = std::min(lo[size_t(a)], positions[3 * v + size_t(a)]);
      hi[size_t(a)] = std::max(hi[size_t(a)], positions[3 * v + size_t(a)]);
    }
  for (int a = 0; a < 3; ++a) {
    // One voxel of margin: the conservative raster marks voxels a triangle only touches. No
    // vertex: an empty box. On a kept layer the box takes in the kept one.
    lo_[size_t(a)] = vertexCount == 0 ? int32_t(s.dims[a])
                                      : std::clamp(int32_t(std::floor(lo[size_t(a)])) - 1, 0,
                                                   int32_t(s.dims[a]));
    hi_[size_t(a)] = vertexCount == 0 ? 0
                                      : std::clamp(int32_t(std::floor(hi[size_t(a)])) + 2, 0,
                                                   int32_t(s.dims[a]));
    if (onKept) {
      lo_[size_t(a)] = std::min(lo_[size_t(a)], keptLo_[size_t(a)]);
      hi_[size_t(a)] = std::max(hi_[size_t(a)], keptHi_[size_t(a)]);
    }
  }
  std::vector<uint32_t> order;
  std::array<uint32_t, 4> first{};
  for (int a = 0; a < 3; ++a) {
    first[size_t(a)] = uint32_t(order.size());
    order.insert(order.end(), byAxis[size_t(a)].begin(), byAxis[size_t(a)].end());
  }
  first[3] = uint32_t(order.size());

  // Geometry buffers grow when a mesh needs more room (the first frame, a bigger mesh).
  if (positions.size() > s.vertexFloats) {
    s.positions = storage(positions.size() * 4);
    s.vertexFloats = positions.size();
  }
  if (triangles.size() > s.triangleIndices) {
    s.indices = storage(triangles.size() * 4);
    s.order = storage(triangles.size() / 3 * 4);
    s.contributions = storage(triangles.size() / 3 * 16);
    s.triangleIndices = triangles.size();
  }
  if (!positions.empty())
    glNamedBufferSubData(s.positions.id(), 0, GLsizeiptr(positions.size() * 4), positions.data());
  if (!triangles.empty()) {
    glNamedBufferSubData(s.indices.id(), 0, GLsizeiptr(triangles.size() * 4), triangles.data());
    glNamedBufferSubData(s.contributions.id(), 0, GLsizeiptr(contributions.size() * 16),
                         contributions.data());
  }
  if (!order.empty())
    glNamedBufferSubData(s.order.id(), 0, GLsizeiptr(order.size() * 4), order.data());

  // Reset (shaders/dynamic_layer_build.comp.glsl): zero and free the pool slots the last update
  // used, sized on the GPU from its count (no read-back); then an empty brick map.
  s.build.use();
  glUniform1ui(s.build.uniform("uBrickCapacity"), GLuint(s.brickCapacity));
  bindPool(s.pool, nullptr);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, s.counters.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, s.dispatchSize.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, s.slotKeys.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 12, s.usedSlots.id());
  glUniform1i(s.build.uniform("uPass"), 0);
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, s.dispatchSize.id());
  glUniform1i(s.build.uniform("uPass"), 1);
  glDispatchComputeIndirect(0);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  const GLuint empty = kEmpty, zero = 0;
  glClearNamedBufferData(s.brickMap.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
  glClearNamedBufferData(s.counters.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  if (onKept) restoreKept();

  // Raster: gl_voxelize adds each fragment's triangle to its voxels in the layer (VXL_DYN_N).
  glUseProgram(s.raster);
  glBindFramebuffer(GL_FRAMEBUFFER, s.framebuffer.id());
  glViewport(0, 0, GLsizei(s.edge), GLsizei(s.edge));
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glBindVertexArray(s.vertexArray);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s.positions.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, s.indices.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, s.order.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, s.brickMap.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, s.contributions.id());
  auto at = [&](const char* name) { return glGetUniformLocation(s.raster, name); };
  glUniform1f(at("uViewportEdge"), float(s.edge));
  glUniform1i(at("uConservative"), 1);
  glUniform3ui(at("uBrickGrid"), s.brickGrid[0], s.brickGrid[1], s.brickGrid[2]);
  glUniform1ui(at("uBrickCapacity"), GLuint(s.brickCapacity));
  for (uint32_t w = 0; w < 3; ++w) {
    if (first[w] == first[w + 1]) continue;
    glUniform1i(at("uAxis"), GLint(w));
    glUniform1ui(at("uFirst"), first[w]);
    glUniform3ui(at("uDims"), s.dims[(w + 1) % 3], s.dims[(w + 2) % 3], s.dims[w]);
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(3 * (first[w + 1] - first[w])));
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  if (GLenum e = glGetError(); e != GL_NO_ERROR)
    return makeError(ErrorCode::kUnsupported, "dynamic layer: GL error 0x", std::hex, e);
  return Status::ok();
}

void GlDynamicLayer::copyKeptBricks(int pass) {
  State& s = *s_;
  const uint64_t n3 = uint64_t(s.brickSize) * s.brickSize * s.brickSize;
  const uint64_t groups = (s.keptBricks * n3 + 63) / 64;
  if (groups == 0) return;
  s.keepCopy.use();
  glUniform1i(s.keepCopy.uniform("uPass"), pass);
  glUniform1ui(s.keepCopy.uniform("uBricks"), GLuint(s.keptBricks));
  bindPool(s.pool, &s.keptPool);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 12, s.usedSlots.id());
  glDispatchCompute(GLuint(std::min<uint64_t>(groups, 32768)), GLuint((groups + 32767) / 32768), 1);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

Status GlDynamicLayer::keep() {
  State& s = *s_;
  VOXLINK_RETURN_IF_ERROR(checkLastUpdate());  // waits; a layer with dropped bricks is no base
  GLuint counters[2] = {0, 0};
  glGetNamedBufferSubData(s.counters.id(), 0, 8, counters);
  const uint64_t bricks = std::min<uint64_t>(counters[0], s.brickCapacity);
  const uint64_t n3 = uint64_t(s.brickSize) * s.brickSize * s.brickSize;
  const uint64_t mapBytes = uint64_t(s.brickGrid[0]) * s.brickGrid[1] * s.brickGrid[2] * 4;
  if (s.keptBrickMap.id() == 0) {
    s.keptBrickMap = storage(mapBytes, 0);
    s.keptSlotKeys = storage(s.brickCapacity * 4, 0);
    s.keptUsedSlots = storage(s.brickCapacity * 4, 0);
    s.keptCounters = storage(8, 0);
  }
  if (bricks > s.keptRoom) {  // grows to what is kept, not to the whole pool; split as the pool
    s.keptPool.clear();
    for (uint64_t k = 0; k < bricks; k += s.slotsPerBuffer)
      s.keptPool.push_back(
          storage(std::min(s.slotsPerBuffer, bricks - k) * n3 * kPoolVoxelBytes, 0));
    s.keptRoom = bricks;
  }
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  copyKeptTables(true);
  s.keptBricks = bricks;
  copyKeptBricks(0);
  keptLo_ = lo_;
  keptHi_ = hi_;
  s.kept = true;
  if (GLenum e = glGetError(); e != GL_NO_ERROR) {
    s.kept = false;
    return makeError(ErrorCode::kTooLarge, "dynamic layer: GL error 0x", std::hex, e, " keeping ",
                     (bricks * n3 * kPoolVoxelBytes) >> 20, " MiB of bricks");
  }
  return Status::ok();
}

// The layer's tables (brick map, slot keys, used slots, counters) into the kept copies, or back.
void GlDynamicLayer::copyKeptTables(bool toKept) {
  State& s = *s_;
  const uint64_t mapBytes = uint64_t(s.brickGrid[0]) * s.brickGrid[1] * s.brickGrid[2] * 4;
  const auto copy = [toKept](const GlBuffer& live, const GlBuffer& kept, uint64_t bytes) {
    glCopyNamedBufferSubData(toKept ? live.id() : kept.id(), toKept ? kept.id() : live.id(), 0, 0,
                             GLsizeiptr(bytes));
  };
  copy(s.brickMap, s.keptBrickMap, mapBytes);
  copy(s.slotKeys, s.keptSlotKeys, s.brickCapacity * 4);
  copy(s.usedSlots, s.keptUsedSlots, s.brickCapacity * 4);
  copy(s.counters, s.keptCounters, 8);
}

// After the reset: the kept layer back (the reset zeroed its slots too; they are overwritten).
void GlDynamicLayer::restoreKept() {
  copyKeptTables(false);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  copyKeptBricks(1);
}

Status GlDynamicLayer::checkLastUpdate() const {
  GLuint counters[2] = {0, 0};  // slots used, bricks dropped
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(s_->counters.id(), 0, 8, counters);
  if (counters[1] > 0)
    return makeError(ErrorCode::kTooLarge, "dynamic layer: ", uint64_t(counters[0]) + counters[1],
                     " bricks exceed its ", s_->brickCapacity, " (", s_->pool.size(),
                     " of at most ", kMaxPoolBuffers, " storage buffers of ", s_->slotsPerBuffer,
                     " bricks; one holds at most GL_MAX_SHADER_STORAGE_BLOCK_SIZE = ",
                     getInteger(GL_MAX_SHADER_STORAGE_BLOCK_SIZE) >> 20, " MiB)");
  return Status::ok();
}

std::vector<std::pair<uint64_t, std::array<int32_t, 4>>> GlDynamicLayer::readVoxels() const {
  const State& s = *s_;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<GLuint> map(uint64_t(s.brickGrid[0]) * s.brickGrid[1] * s.brickGrid[2]);
  glGetNamedBufferSubData(s.brickMap.id(), 0, GLsizeiptr(map.size() * 4), map.data());
  const uint32_t n = s.brickSize, n3 = n * n * n;
  std::vector<std::array<int32_t, 4>> brick(n3);
  std::vector<std::pair<uint64_t, std::array<int32_t, 4>>> out;
  for (uint32_t bz = 0; bz < s.brickGrid[2]; ++bz)
    for (uint32_t by = 0; by < s.brickGrid[1]; ++by)
      for (uint32_t bx = 0; bx < s.brickGrid[0]; ++bx) {
        const GLuint slot = map[(uint64_t(bz) * s.brickGrid[1] + by) * s.brickGrid[0] + bx];
        if (slot == kEmpty || slot >= s.brickCapacity) continue;
        glGetNamedBufferSubData(s.pool[slot / s.slotsPerBuffer].id(),
                                GLintptr(uint64_t(slot % s.slotsPerBuffer) * n3 * kPoolVoxelBytes),
                                GLsizeiptr(n3 * kPoolVoxelBytes), brick.data());
        for (uint32_t k = 0; k < n3; ++k)
          if (brick[k][3] != 0)
            out.push_back(
                {geometry::voxelKey(bx * n + k % n, by * n + k / n % n, bz * n + k / (n * n)),
                 brick[k]});
      }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace voxlink::render::gl
