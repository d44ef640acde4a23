// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/gl_dynamic_spheres.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "render/gl/detail/gl_objects.h"
#include "render/gl/shader_program.h"

namespace voxlink::render::gl {
namespace {

constexpr GLuint kEmpty = 0xffffffffu;
constexpr uint64_t kSphereBytes = 32;  // 8 words, as format::SphereRecord
constexpr uint64_t kNodeBytes = 8;     // uvec2: sphere, next
// A sphere is listed in every brick within this many voxels of its ball: the tracer's float hit
// point lies within about 1e-4 voxels of the sphere at 1024 voxels, so none is missed.
constexpr double kMarginVoxels = 0.01;

GLint getInteger(GLenum name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

GlBuffer storage(uint64_t bytes) {
  GlBuffer b = createBuffer();
  glNamedBufferStorage(b.id(), GLsizeiptr(std::max<uint64_t>(bytes, 16)), nullptr,
                       GL_DYNAMIC_STORAGE_BIT);
  return b;
}

}  // namespace

struct GlDynamicSpheres::State {
  std::array<uint32_t, 3> dims{}, brickGrid{};
  std::array<double, 3> origin{};
  double spacing = 1;
  uint32_t brickSize = 8;
  uint64_t capacity = 0, sphereRoom = 0;
  // Brick heads written since the lists were last emptied or set back to the kept part.
  uint64_t dirtyFirst = 0, dirtyEnd = 0;
  ComputeProgram mark;
  GlBuffer heads, nodes, spheres, counters;
  // The kept part: the heads and counters as keep() found them, and the heads it had written.
  GlBuffer keptHeads, keptCounters;
  uint64_t keptDirtyFirst = 0, keptDirtyEnd = 0;
  bool hasKept = false;
};

GlDynamicSpheres::GlDynamicSpheres(std::unique_ptr<State> state) : s_(std::move(state)) {}
GlDynamicSpheres::GlDynamicSpheres(GlDynamicSpheres&&) noexcept = default;
GlDynamicSpheres& GlDynamicSpheres::operator=(GlDynamicSpheres&&) noexcept = default;
GlDynamicSpheres::~GlDynamicSpheres() = default;
GLuint GlDynamicSpheres::heads() const { return s_->heads.id(); }
GLuint GlDynamicSpheres::nodes() const { return s_->nodes.id(); }
GLuint GlDynamicSpheres::spheres() const { return s_->spheres.id(); }
uint32_t GlDynamicSpheres::brickSize() const { return s_->brickSize; }

uint64_t GlDynamicSpheres::gpuBytes() const {
  const uint64_t bricks = uint64_t(s_->brickGrid[0]) * s_->brickGrid[1] * s_->brickGrid[2];
  const uint64_t kept = s_->keptHeads.id() ? bricks * 4 + 8 : 0;
  return bricks * 4 + s_->capacity * kNodeBytes + s_->sphereRoom * kSphereBytes + 8 + kept;
}

Result<GlDynamicSpheres> GlDynamicSpheres::create(const std::array<uint32_t, 3>& dims,
                                                  const std::array<double, 3>& origin,
                                                  double spacing, uint32_t brickSize,
                                                  uint64_t referenceCapacity) {
  auto s = std::make_unique<State>();
  s->dims = dims;
  s->origin = origin;
  s->spacing = spacing;
  s->brickSize = brickSize;
  for (int a = 0; a < 3; ++a) s->brickGrid[a] = (dims[a] + brickSize - 1) / brickSize;
  const uint64_t maxBlock = uint64_t(std::max(getInteger(GL_MAX_SHADER_STORAGE_BLOCK_SIZE), 0));
  s->capacity = std::max<uint64_t>(1, std::min(referenceCapacity, maxBlock / kNodeBytes));
  VOXLINK_ASSIGN_OR_RETURN(s->mark, ComputeProgram::build("dynamic_spheres_mark.comp.glsl",
                                                          {{"VXL_N", std::to_string(brickSize)}}));
  const uint64_t bricks = uint64_t(s->brickGrid[0]) * s->brickGrid[1] * s->brickGrid[2];
  s->heads = storage(bricks * 4);
  s->nodes = storage(s->capacity * kNodeBytes);
  s->counters = storage(8);
  const GLuint empty = kEmpty, zero = 0;
  glClearNamedBufferData(s->heads.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
  glClearNamedBufferData(s->counters.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  if (GLenum e = glGetError(); e != GL_NO_ERROR)
    return makeError(ErrorCode::kTooLarge, "dynamic spheres: GL error 0x", std::hex, e,
                     " allocating ", (s->capacity * kNodeBytes) >> 20, " MiB of references");
  GlDynamicSpheres layer(std::move(s));
  layer.lo_ = {int32_t(dims[0]), int32_t(dims[1]), int32_t(dims[2])};  // empty until an update
  return layer;
}

Status GlDynamicSpheres::update(const std::vector<DynamicSphere>& spheres) {
  reset(false);
  return mark(0, spheres);
}

void GlDynamicSpheres::reset(bool onKept) {
  State& s = *s_;
  const GLuint empty = kEmpty, zero = 0;
  if (onKept && s.hasKept) {
    // The heads the kept part or a mark since wrote, back to the kept part's; its nodes are
    // untouched (marks after it only take nodes past its count).
    const uint64_t first = std::min(s.dirtyFirst, s.keptDirtyFirst);
    const uint64_t end = std::max(s.dirtyEnd, s.keptDirtyEnd);
    if (end > first)
      glCopyNamedBufferSubData(s.keptHeads.id(), s.heads.id(), GLintptr(first * 4),
                               GLintptr(first * 4), GLsizeiptr((end - first) * 4));
    glCopyNamedBufferSubData(s.keptCounters.id(), s.counters.id(), 0, 0, 8);
    s.dirtyFirst = s.keptDirtyFirst;
    s.dirtyEnd = s.keptDirtyEnd;
    lo_ = keptLo_;
    hi_ = keptHi_;
  } else {
    forgetKept();  // its nodes are about to be overwritten
    if (s.dirtyEnd > s.dirtyFirst)
      glClearNamedBufferSubData(s.heads.id(), GL_R32UI, GLintptr(s.dirtyFirst * 4),
                                GLsizeiptr((s.dirtyEnd - s.dirtyFirst) * 4), GL_RED_INTEGER,
                                GL_UNSIGNED_INT, &empty);
    glClearNamedBufferData(s.counters.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    s.dirtyFirst = s.dirtyEnd = 0;
    lo_ = {int32_t(s.dims[0]), int32_t(s.dims[1]), int32_t(s.dims[2])};
    hi_ = {0, 0, 0};
  }
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

Status GlDynamicSpheres::mark(uint32_t first, const std::vector<DynamicSphere>& spheres) {
  State& s = *s_;
  if (spheres.empty()) return Status::ok();
  // The records (8 words: centre, radius, material, unused) and the voxel box of the balls.
  std::vector<uint32_t> words(spheres.size() * 8, 0);
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (size_t i = 0; i < spheres.size(); ++i) {
    const DynamicSphere& sp = spheres[i];
    std::memcpy(&words[i * 8], sp.centre.data(), 12);
    std::memcpy(&words[i * 8 + 3], &sp.radius, 4);
    words[i * 8 + 4] = sp.material;
    const double r = sp.radius / s.spacing + kMarginVoxels;
    for (int a = 0; a < 3; ++a) {
      const double c = (sp.centre[size_t(a)] - s.origin[size_t(a)]) / s.spacing + 0.5;
      lo[size_t(a)] = std::min(lo[size_t(a)], c - r);
      hi[size_t(a)] = std::max(hi[size_t(a)], c + r);
    }
  }
  std::array<int32_t, 3> markLo{}, markHi{};
  for (int a = 0; a < 3; ++a) {
    const int32_t dim = int32_t(s.dims[size_t(a)]);
    markLo[size_t(a)] = std::clamp(int32_t(std::floor(lo[size_t(a)])), 0, dim);
    markHi[size_t(a)] = std::clamp(int32_t(std::floor(hi[size_t(a)])) + 1, 0, dim);
    lo_[size_t(a)] = std::min(lo_[size_t(a)], markLo[size_t(a)]);
    hi_[size_t(a)] = std::max(hi_[size_t(a)], markHi[size_t(a)]);
  }
  const uint64_t end = uint64_t(first) + spheres.size();
  if (end > s.sphereRoom) {  // grown, keeping the records of spheres marked before
    GlBuffer grown = storage(end * kSphereBytes);
    if (s.sphereRoom > 0)
      glCopyNamedBufferSubData(s.spheres.id(), grown.id(), 0, 0,
                               GLsizeiptr(s.sphereRoom * kSphereBytes));
    s.spheres = std::move(grown);
    s.sphereRoom = end;
  }
  glNamedBufferSubData(s.spheres.id(), GLintptr(uint64_t(first) * kSphereBytes),
                       GLsizeiptr(words.size() * 4), words.data());
  // The heads this mark may write: the brick slabs (z) of its box, added to the reset's range.
  if (markLo[2] < markHi[2]) {
    const uint64_t slab = uint64_t(s.brickGrid[0]) * s.brickGrid[1];
    const uint64_t slabFirst = uint64_t(markLo[2] / int32_t(s.brickSize)) * slab;
    const uint64_t slabEnd = uint64_t((markHi[2] - 1) / int32_t(s.brickSize) + 1) * slab;
    const bool none = s.dirtyEnd <= s.dirtyFirst;
    s.dirtyFirst = none ? slabFirst : std::min(s.dirtyFirst, slabFirst);
    s.dirtyEnd = none ? slabEnd : std::max(s.dirtyEnd, slabEnd);
  }
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);

  s.mark.use();
  glUniform1ui(s.mark.uniform("uFirstSphere"), GLuint(first));
  glUniform1ui(s.mark.uniform("uSphereCount"), GLuint(spheres.size()));
  glUniform1ui(s.mark.uniform("uCapacity"), GLuint(s.capacity));
  glUniform3f(s.mark.uniform("uOrigin"), float(s.origin[0]), float(s.origin[1]),
              float(s.origin[2]));
  glUniform1f(s.mark.uniform("uSpacing"), float(s.spacing));
  glUniform1f(s.mark.uniform("uMargin"), float(kMarginVoxels));
  glUniform3i(s.mark.uniform("uBrickGrid"), GLint(s.brickGrid[0]), GLint(s.brickGrid[1]),
              GLint(s.brickGrid[2]));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, s.spheres.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, s.heads.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, s.nodes.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, s.counters.id());
  const uint64_t groups = (spheres.size() + 63) / 64;
  glDispatchCompute(GLuint(std::min<uint64_t>(groups, 32768)), GLuint((groups + 32767) / 32768), 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  if (GLenum e = glGetError(); e != GL_NO_ERROR)
    return makeError(ErrorCode::kUnsupported, "dynamic spheres: GL error 0x", std::hex, e);
  return Status::ok();
}

Status GlDynamicSpheres::keep() {
  State& s = *s_;
  const uint64_t bricks = uint64_t(s.brickGrid[0]) * s.brickGrid[1] * s.brickGrid[2];
  if (!s.keptHeads.id()) {  // made on the first keep: scenes with one sphere set never need it
    s.keptHeads = storage(bricks * 4);
    s.keptCounters = storage(8);
  }
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  glCopyNamedBufferSubData(s.heads.id(), s.keptHeads.id(), 0, 0, GLsizeiptr(bricks * 4));
  glCopyNamedBufferSubData(s.counters.id(), s.keptCounters.id(), 0, 0, 8);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  s.keptDirtyFirst = s.dirtyFirst;
  s.keptDirtyEnd = s.dirtyEnd;
  keptLo_ = lo_;
  keptHi_ = hi_;
  s.hasKept = true;
  if (GLenum e = glGetError(); e != GL_NO_ERROR)
    return makeError(ErrorCode::kTooLarge, "dynamic spheres: GL error 0x", std::hex, e,
                     " keeping the lists");
  return Status::ok();
}

void GlDynamicSpheres::forgetKept() { s_->hasKept = false; }
bool GlDynamicSpheres::hasKept() const { return s_->hasKept; }

Status GlDynamicSpheres::checkLastUpdate() const {
  GLuint counters[2] = {0, 0};  // references made, references dropped
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(s_->counters.id(), 0, 8, counters);
  if (counters[1] > 0)
    return makeError(ErrorCode::kTooLarge, "dynamic spheres: ", uint64_t(counters[0]),
                     " sphere references exceed room for ", s_->capacity);
  return Status::ok();
}

std::vector<std::vector<uint32_t>> GlDynamicSpheres::readLists() const {
  const State& s = *s_;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<GLuint> heads(uint64_t(s.brickGrid[0]) * s.brickGrid[1] * s.brickGrid[2]);
  glGetNamedBufferSubData(s.heads.id(), 0, GLsizeiptr(heads.size() * 4), heads.data());
  std::vector<GLuint> nodes(s.capacity * 2);
  glGetNamedBufferSubData(s.nodes.id(), 0, GLsizeiptr(nodes.size() * 4), nodes.data());
  std::vector<std::vector<uint32_t>> lists(heads.size());
  for (size_t b = 0; b < heads.size(); ++b) {
    for (GLuint n = heads[b]; n != kEmpty && n < s.capacity; n = nodes[2 * n + 1])
      lists[b].push_back(nodes[2 * n]);
    std::sort(lists[b].begin(), lists[b].end());
  }
  return lists;
}

}  // namespace voxlink::render::gl
