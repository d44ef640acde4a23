// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/gl_voxelizer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "geometry/fragment_resolve.h"
#include "render/gl/detail/gl_objects.h"
#include "render/gl/shader_program.h"

namespace voxlink::render::gl {
namespace {

using Clock = std::chrono::steady_clock;
constexpr GLuint kEmpty = 0xffffffffu;
constexpr size_t kFragmentBytes = 16;  // uvec4 in gl_voxelize.frag.glsl

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Result<GLuint> linkVoxelizerProgram() {
  VOXLINK_ASSIGN_OR_RETURN(GLuint vertex,
                           compileShaderStage(GL_VERTEX_SHADER, "gl_voxelize.vert.glsl"));
  auto fragment = compileShaderStage(GL_FRAGMENT_SHADER, "gl_voxelize.frag.glsl");
  if (!fragment) {
    glDeleteShader(vertex);
    return fragment.error();
  }
  return linkProgram({vertex, *fragment}, "gl_voxelize");
}

GLint getInteger(GLenum name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

}  // namespace

Result<GlSurfaceVoxelizer> GlSurfaceVoxelizer::create() {
  VOXLINK_ASSIGN_OR_RETURN(GLuint program, linkVoxelizerProgram());
  GlSurfaceVoxelizer v;
  v.program_ = program;
  glCreateVertexArrays(1, &v.vertexArray_);  // empty: the vertex stage reads storage buffers
  glCreateFramebuffers(1, &v.framebuffer_);  // no attachments: fragments only write buffers
  return v;
}

GlSurfaceVoxelizer::GlSurfaceVoxelizer(GlSurfaceVoxelizer&& other) noexcept
    : program_(std::exchange(other.program_, 0)),
      vertexArray_(std::exchange(other.vertexArray_, 0)),
      framebuffer_(std::exchange(other.framebuffer_, 0)) {}

GlSurfaceVoxelizer& GlSurfaceVoxelizer::operator=(GlSurfaceVoxelizer&& other) noexcept {
  std::swap(program_, other.program_);
  std::swap(vertexArray_, other.vertexArray_);
  std::swap(framebuffer_, other.framebuffer_);
  return *this;
}

GlSurfaceVoxelizer::~GlSurfaceVoxelizer() {
  if (program_) glDeleteProgram(program_);
  if (vertexArray_) glDeleteVertexArrays(1, &vertexArray_);
  if (framebuffer_) glDeleteFramebuffers(1, &framebuffer_);
}

Result<GlSurfaceVoxelization> GlSurfaceVoxelizer::voxelize(const geometry::TriangleMesh& mesh,
                                                           const geometry::VoxelGrid& grid,
                                                           const GlVoxelizeOptions& options) {
  VOXLINK_RETURN_IF_ERROR(geometry::validateGrid(grid));
  const size_t vertexCount = mesh.vertexCount();
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    if (mesh.triangles[i] >= vertexCount)
      return makeError(ErrorCode::kInvalidArgument, "mesh: triangle ", i / 3, ": vertex index ",
                       mesh.triangles[i], " >= vertex count ", vertexCount);
  if (!mesh.triangleMaterials.empty() && mesh.triangleMaterials.size() != mesh.triangleCount())
    return makeError(ErrorCode::kSizeMismatch, "mesh: ", mesh.triangleMaterials.size(),
                     " triangle materials for ", mesh.triangleCount(), " triangles");
  GlSurfaceVoxelization out;
  const auto rasterStart = Clock::now();

  // Grid coordinates (double, then float for the GPU) and the triangles binned by dominant axis
  // with the exact path's tie rule; zero-area triangles are skipped as there.
  std::vector<float> positions(mesh.positions.size());
  for (size_t v = 0; v < vertexCount; ++v) {
    const auto g =
        grid.toGrid(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
    for (int a = 0; a < 3; ++a) positions[3 * v + size_t(a)] = float(g[size_t(a)]);
  }
  std::array<std::vector<uint32_t>, 3> byAxis;
  std::vector<float> estimate(mesh.triangleCount(), 0.0f);  // expected fragments per triangle
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    std::array<double, 3> c[3];
    for (int k = 0; k < 3; ++k) {
      const float* p = &mesh.positions[3 * size_t(mesh.triangles[3 * t + size_t(k)])];
      c[k] = grid.toGrid(p[0], p[1], p[2]);
    }
    const double e1[3] = {c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2]};
    const double e2[3] = {c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2]};
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    if (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0) {
      ++out.stats.zeroAreaTriangles;
      continue;
    }
    int w = 0;
    if (std::abs(n[1]) > std::abs(n[w])) w = 1;
    if (std::abs(n[2]) > std::abs(n[w])) w = 2;
    byAxis[size_t(w)].push_back(uint32_t(t));
    double pixels = 0.5 * std::abs(n[w]) + 1.0;         // projected area
    if (options.coverage == GlCoverage::kConservative)  // pixels along the edges, and corners
      for (int k = 0; k < 3; ++k) {
        const auto& a = c[k];
        const auto& b = c[(k + 1) % 3];
        pixels += std::abs(a[size_t(w + 1) % 3] - b[size_t(w + 1) % 3]) +
                  std::abs(a[size_t(w + 2) % 3] - b[size_t(w + 2) % 3]) + 1.0;
      }
    estimate[t] = float(pixels);
  }
  out.surface.zeroAreaTriangles = out.stats.zeroAreaTriangles;
  std::vector<uint32_t> order;
  std::array<uint32_t, 4> first{};
  for (int a = 0; a < 3; ++a) {
    first[size_t(a)] = uint32_t(order.size());
    order.insert(order.end(), byAxis[size_t(a)].begin(), byAxis[size_t(a)].end());
  }
  first[3] = uint32_t(order.size());
  if (order.empty()) {
    out.stats.rasterSeconds = secondsSince(rasterStart);
    return out;
  }

  // A square viewport covers every axis pair; pixel (u, v) is the column through voxel (u, v).
  const uint32_t edge = std::max({grid.dims[0], grid.dims[1], grid.dims[2]});
  GLint viewportMax[2] = {0, 0};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewportMax);
  const GLint framebufferMax =
      std::min(getInteger(GL_MAX_FRAMEBUFFER_WIDTH), getInteger(GL_MAX_FRAMEBUFFER_HEIGHT));
  if (int64_t(edge) >
      std::min({int64_t(viewportMax[0]), int64_t(viewportMax[1]), int64_t(framebufferMax)}))
    return makeError(ErrorCode::kTooLarge, "GL voxelizer: grid edge ", edge,
                     " exceeds the largest viewport/framebuffer (", viewportMax[0], ")");
  const uint64_t maxBlock = uint64_t(std::max(getInteger(GL_MAX_SHADER_STORAGE_BLOCK_SIZE), 0));
  const uint64_t columns = 3ull * edge * edge;
  if (columns * 4 > maxBlock)
    return makeError(ErrorCode::kTooLarge, "GL voxelizer: ", columns * 4 >> 20,
                     " MiB of column heads at grid edge ", edge,
                     " exceed the largest storage buffer (", maxBlock >> 20, " MiB)");
  const uint64_t maxFragments = maxBlock / kFragmentBytes;
  // Batches of triangles whose expected fragments fill at most half the largest buffer (and 64
  // MiB), so that a mesh of any size voxelizes in bounded GPU memory; each batch is drawn,
  // read back and its lists walked before the next.
  const double batchBudget =
      double(options.batchFragments > 0
                 ? std::min(options.batchFragments, maxFragments / 2)
                 : std::min<uint64_t>(maxFragments / 2, (64ull << 20) / kFragmentBytes));
  std::vector<std::pair<uint32_t, uint32_t>> batches;  // ranges of `order`
  {
    double sum = 0.0;
    uint32_t begin = 0;
    for (uint32_t i = 0; i < order.size(); ++i) {
      if (i > begin && sum + estimate[order[i]] > batchBudget) {
        batches.push_back({begin, i});
        begin = i;
        sum = 0.0;
      }
      sum += estimate[order[i]];
    }
    batches.push_back({begin, uint32_t(order.size())});
  }

  GlStorageBuffer positionBuffer =
      createStorageBuffer(positions.data(), positions.size() * sizeof(float));
  GlStorageBuffer indexBuffer =
      createStorageBuffer(mesh.triangles.data(), mesh.triangles.size() * sizeof(uint32_t));
  GlStorageBuffer orderBuffer = createStorageBuffer(order.data(), order.size() * sizeof(uint32_t));
  GlBuffer heads = createBuffer();
  glNamedBufferStorage(heads.id(), GLsizeiptr(columns * 4), nullptr,
                       GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
  GlBuffer counter = createBuffer();
  glNamedBufferStorage(counter.id(), sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT);

  glUseProgram(program_);
  glNamedFramebufferParameteri(framebuffer_, GL_FRAMEBUFFER_DEFAULT_WIDTH, GLint(edge));
  glNamedFramebufferParameteri(framebuffer_, GL_FRAMEBUFFER_DEFAULT_HEIGHT, GLint(edge));
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, GLsizei(edge), GLsizei(edge));
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glBindVertexArray(vertexArray_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, heads.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, positionBuffer.buffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, indexBuffer.buffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, orderBuffer.buffer.id());
  glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, counter.id());
  glUniform1f(glGetUniformLocation(program_, "uViewportEdge"), float(edge));
  glUniform1ui(glGetUniformLocation(program_, "uColumns"), edge);
  glUniform1i(glGetUniformLocation(program_, "uConservative"),
              options.coverage == GlCoverage::kConservative);
  out.stats.rasterSeconds = secondsSince(rasterStart);

  std::vector<geometry::VoxelTriangle> pairs;
  std::vector<GLuint> headList(columns);
  std::vector<std::array<GLuint, 4>> list;
  std::vector<std::pair<float, uint32_t>> column;  // depth, fragment slot
  for (const auto& [batchBegin, batchEnd] : batches) {
    const auto batchStart = Clock::now();
    double expected = 0.0;
    for (uint32_t i = batchBegin; i < batchEnd; ++i) expected += estimate[order[i]];
    uint64_t capacity = std::min<uint64_t>(maxFragments, uint64_t(expected * 1.1) + 1024);
    GlBuffer fragments;
    GLuint count = 0;
    for (int attempt = 0;; ++attempt) {
      fragments = createBuffer();
      glNamedBufferStorage(fragments.id(), GLsizeiptr(capacity * kFragmentBytes), nullptr, 0);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, fragments.id());
      const GLuint empty = kEmpty, zero = 0;
      glClearNamedBufferData(heads.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
      glClearNamedBufferData(counter.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT);
      glUniform1ui(glGetUniformLocation(program_, "uCapacity"), GLuint(capacity));
      for (uint32_t w = 0; w < 3; ++w) {
        const uint32_t from = std::max(batchBegin, first[w]);
        const uint32_t to = std::min(batchEnd, first[w + 1]);
        if (from >= to) continue;
        glUniform1i(glGetUniformLocation(program_, "uAxis"), GLint(w));
        glUniform1ui(glGetUniformLocation(program_, "uFirst"), from);
        glUniform3ui(glGetUniformLocation(program_, "uDims"), grid.dims[(w + 1) % 3],
                     grid.dims[(w + 2) % 3], grid.dims[w]);
        glDrawArrays(GL_TRIANGLES, 0, GLsizei(3 * (to - from)));
      }
      ++out.stats.draws;
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT);
      glGetNamedBufferSubData(counter.id(), 0, sizeof(GLuint), &count);
      if (count <= capacity) break;
      if (count > maxFragments || attempt > 0)
        return makeError(ErrorCode::kTooLarge, "GL voxelizer: ", count, " fragments exceed ",
                         maxFragments, " (the largest storage buffer) at grid ", grid.dims[0], "x",
                         grid.dims[1], "x", grid.dims[2]);
      capacity = count;  // the exact need: the second pass fits
    }
    glFinish();
    if (GLenum e = glGetError(); e != GL_NO_ERROR)
      return makeError(ErrorCode::kUnsupported, "GL voxelizer: GL error 0x", std::hex, e);
    out.stats.fragments += count;
    out.stats.rasterSeconds += secondsSince(batchStart);

    const auto readStart = Clock::now();
    glGetNamedBufferSubData(heads.id(), 0, GLsizeiptr(columns * 4), headList.data());
    list.resize(count);
    if (count > 0)
      glGetNamedBufferSubData(fragments.id(), 0, GLsizeiptr(uint64_t(count) * kFragmentBytes),
                              list.data());
    out.stats.readbackSeconds += secondsSince(readStart);

    // Each column's list sorted by depth (the paper's order along the predominant axis), then
    // unswizzled into (voxel, triangle) pairs.
    const auto walkStart = Clock::now();
    for (uint32_t w = 0; w < 3; ++w) {
      const uint32_t u = (w + 1) % 3, v = (w + 2) % 3;
      for (uint32_t cv = 0; cv < grid.dims[v]; ++cv)
        for (uint32_t cu = 0; cu < grid.dims[u]; ++cu) {
          GLuint slot = headList[(uint64_t(w) * edge + cv) * edge + cu];
          column.clear();
          while (slot != kEmpty) {
            if (slot >= count || column.size() > count)
              return makeError(ErrorCode::kCorrupt, "GL voxelizer: broken fragment list");
            const auto& f = list[slot];
            float depth;
            std::memcpy(&depth, &f[3], sizeof depth);
            column.push_back({depth, slot});
            slot = f[2];
          }
          std::sort(column.begin(), column.end());
          for (const auto& [depth, s] : column) {
            std::array<uint32_t, 3> index{};
            index[u] = cu;
            index[v] = cv;
            for (uint32_t k = list[s][0] & 0xffff; k <= list[s][0] >> 16; ++k) {
              index[w] = k;
              pairs.push_back({geometry::voxelKey(index[0], index[1], index[2]), list[s][1]});
            }
          }
        }
    }
    out.stats.resolveSeconds += secondsSince(walkStart);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  const auto resolveStart = Clock::now();
  VOXLINK_ASSIGN_OR_RETURN(
      out.surface, geometry::resolveVoxelTriangles(mesh, grid, std::move(pairs), options.resolve));
  out.surface.zeroAreaTriangles = out.stats.zeroAreaTriangles;
  out.stats.resolveSeconds += secondsSince(resolveStart);
  return out;
}

}  // namespace voxlink::render::gl
