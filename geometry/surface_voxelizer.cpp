// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/surface_voxelizer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>

#include "base/parallel_for.h"
#include "geometry/detail/triangle_box_overlap.h"
#include "geometry/normal_error.h"

namespace voxlink::geometry {
namespace {

struct Overlap {
  uint64_t key;
  uint32_t triangle;
  bool operator<(const Overlap& o) const {
    return key != o.key ? key < o.key : triangle < o.triangle;
  }
};

struct TriangleInfo {
  std::array<float, 3> normal;  // unit
  float area;                   // in voxel units (only compared)
};

// Appends the voxels `tri` overlaps (clipped to the grid and the slab) to `out`.
void collectTriangle(const TriangleVoxelTest& test, uint32_t tri, const VoxelGrid& grid,
                     const ZSlab& slab, std::vector<Overlap>& out) {
  int64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::max<int64_t>(test.firstVoxel(a), 0);
    hi[a] = std::min<int64_t>(test.lastVoxel(a), int64_t(grid.dims[a]) - 1);
  }
  lo[2] = std::max<int64_t>(lo[2], slab.begin);
  hi[2] = std::min<int64_t>(hi[2], int64_t(slab.end) - 1);
  for (int a = 0; a < 3; ++a)
    if (lo[a] > hi[a]) return;
  const Vec3d& n = test.normal();
  // Columns along the dominant normal axis w; (u, v) as in the projection test of w.
  int w = 0;
  if (std::abs(n[1]) > std::abs(n[w])) w = 1;
  if (std::abs(n[2]) > std::abs(n[w])) w = 2;
  const int u = (w + 1) % 3, v = (w + 2) % 3;
  int64_t index[3];
  for (int64_t iu = lo[u]; iu <= hi[u]; ++iu) {
    for (int64_t iv = lo[v]; iv <= hi[v]; ++iv) {
      if (!test.projectionOverlaps(w, double(iu), double(iv))) continue;
      // Where the plane crosses this column: a candidate range, widened by one voxel against
      // rounding; every candidate still gets the full test.
      const double cu = iu + 0.5, cv = iv + 0.5;
      const double nw = n[w];
      const double centre = (test.planeOffset() - n[u] * cu - n[v] * cv) / nw;
      const double half = 0.5 * (std::abs(n[u]) + std::abs(n[v])) / std::abs(nw);
      const int64_t from = std::max<int64_t>(lo[w], int64_t(std::floor(centre - half)) - 1);
      const int64_t to = std::min<int64_t>(hi[w], int64_t(std::floor(centre + half)) + 1);
      index[u] = iu;
      index[v] = iv;
      for (int64_t iw = from; iw <= to; ++iw) {
        index[w] = iw;
        if (!test.overlaps(index[0], index[1], index[2])) continue;
        out.push_back({voxelKey(uint32_t(index[0]), uint32_t(index[1]), uint32_t(index[2])), tri});
      }
    }
  }
}

Status validate(const TriangleMesh& mesh) {
  const size_t vertices = mesh.vertexCount();
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (mesh.triangles[i] >= vertices) {
      return makeError(ErrorCode::kInvalidArgument, "mesh: triangle ", i / 3, ": vertex index ",
                       mesh.triangles[i], " >= vertex count ", vertices);
    }
  }
  if (!mesh.triangleMaterials.empty() && mesh.triangleMaterials.size() != mesh.triangleCount()) {
    return makeError(ErrorCode::kSizeMismatch, "mesh: ", mesh.triangleMaterials.size(),
                     " triangle materials for ", mesh.triangleCount(), " triangles");
  }
  return Status::ok();
}

}  // namespace

Result<SurfaceVoxelization> voxelizeSurface(const TriangleMesh& mesh, const VoxelGrid& grid,
                                            const SurfaceVoxelizeOptions& options) {
  VOXLINK_RETURN_IF_ERROR(validateGrid(grid));
  VOXLINK_RETURN_IF_ERROR(validate(mesh));
  const size_t triangleCount = mesh.triangleCount();
  SurfaceVoxelization result;
  if (triangleCount == 0) return result;

  // Pass 1: per triangle, its unit normal and area, and the voxels it overlaps. Triangles are
  // cut into at most kMaxBlocks fixed blocks so that the overlaps can be put in order without a
  // global sort: a stable counting sort by z over blocks in triangle order, then a small sort
  // per z slice.
  constexpr size_t kMaxBlocks = 64;
  const size_t blockSize = std::max<size_t>(1024, (triangleCount + kMaxBlocks - 1) / kMaxBlocks);
  const size_t blockCount = (triangleCount + blockSize - 1) / blockSize;
  const size_t depth = grid.dims[2];
  std::vector<TriangleInfo> info(triangleCount);
  std::vector<std::vector<Overlap>> blocks(blockCount);
  std::vector<uint64_t> perSlice(blockCount * depth, 0);  // [block][z] overlap counts
  std::atomic<uint64_t> total{0}, zeroArea{0};
  std::atomic<bool> tooMany{false};
  // Progress: pass 1 (the overlap tests) is 80 % of the work, the sorting passes the rest.
  std::mutex progressMutex;
  size_t blocksDone = 0;
  auto report = [&](double fraction) {
    if (!options.progress) return;
    std::lock_guard<std::mutex> lock(progressMutex);
    options.progress(fraction);
  };
  auto blockDone = [&] {
    if (!options.progress) return;
    std::lock_guard<std::mutex> lock(progressMutex);
    options.progress(0.8 * double(++blocksDone) / double(blockCount));
  };
  base::parallelFor(blockCount, 0, [&](uint64_t block) {
    std::vector<Overlap>& out = blocks[block];
    uint64_t zero = 0;
    const size_t end = std::min(triangleCount, (block + 1) * blockSize);
    for (size_t t = block * blockSize; t < end && !tooMany; ++t) {
      Vec3d corner[3];
      for (int c = 0; c < 3; ++c) {
        const float* p = &mesh.positions[3 * size_t(mesh.triangles[3 * t + c])];
        corner[c] = grid.toGrid(p[0], p[1], p[2]);
      }
      const TriangleVoxelTest test(corner[0], corner[1], corner[2]);
      const Vec3d& n = test.normal();
      const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(length > 0.0)) {
        info[t] = {{0.0f, 0.0f, 0.0f}, 0.0f};
        ++zero;
        continue;
      }
      info[t] = {{float(n[0] / length), float(n[1] / length), float(n[2] / length)},
                 float(0.5 * length)};
      const size_t before = out.size();
      collectTriangle(test, uint32_t(t), grid, options.slab, out);
      if (total.fetch_add(out.size() - before) + (out.size() - before) > options.maxOverlaps)
        tooMany = true;
    }
    uint64_t* counts = &perSlice[block * depth];
    for (const Overlap& o : out) ++counts[o.key >> 32];
    zeroArea += zero;
    blockDone();
  });
  if (tooMany) {
    return makeError(ErrorCode::kTooLarge, "surface voxelizer: more than ", options.maxOverlaps,
                     " voxel/triangle overlaps at grid ", grid.dims[0], "x", grid.dims[1], "x",
                     grid.dims[2]);
  }
  result.zeroAreaTriangles = zeroArea;

  // Pass 2: scatter by z (slice z, then block order), then sort each slice by (key, triangle).
  std::vector<uint64_t> sliceStart(depth + 1, 0);
  for (size_t z = 0; z < depth; ++z) {
    uint64_t sum = 0;
    for (size_t block = 0; block < blockCount; ++block) sum += perSlice[block * depth + z];
    sliceStart[z + 1] = sliceStart[z] + sum;
  }
  // perSlice becomes each block's write position in each slice.
  for (size_t z = 0; z < depth; ++z) {
    uint64_t at = sliceStart[z];
    for (size_t block = 0; block < blockCount; ++block) {
      const uint64_t count = perSlice[block * depth + z];
      perSlice[block * depth + z] = at;
      at += count;
    }
  }
  const size_t overlapCount = sliceStart[depth];
  std::unique_ptr<Overlap[]> overlaps(new Overlap[overlapCount]);  // not zero-filled
  base::parallelFor(blockCount, 0, [&](uint64_t block) {
    uint64_t* at = &perSlice[block * depth];
    for (const Overlap& o : blocks[block]) overlaps[at[o.key >> 32]++] = o;
    std::vector<Overlap>().swap(blocks[block]);
  });
  // Within a slice the overlaps are in triangle order; a stable counting sort by y and a stable
  // insertion sort by x per row (rows hold a few overlaps) give (key, triangle) order.
  struct SliceScratch {
    std::vector<Overlap> buffer;
    std::vector<uint32_t> rowStart;
  };
  const unsigned workers = base::threadCount(0);
  std::vector<SliceScratch> scratch(workers);  // one per worker
  const size_t rows = grid.dims[1];
  base::parallelFor(depth, workers, [&](uint64_t z, unsigned worker) {
    Overlap* slice = overlaps.get() + sliceStart[z];
    const size_t count = sliceStart[z + 1] - sliceStart[z];
    if (count < 2) return;
    SliceScratch& tmp = scratch[worker];
    tmp.buffer.resize(count);
    tmp.rowStart.assign(rows + 1, 0);
    for (size_t i = 0; i < count; ++i) ++tmp.rowStart[((slice[i].key >> 16) & 0xffff) + 1];
    for (size_t y = 0; y < rows; ++y) tmp.rowStart[y + 1] += tmp.rowStart[y];
    for (size_t i = 0; i < count; ++i)
      tmp.buffer[tmp.rowStart[(slice[i].key >> 16) & 0xffff]++] = slice[i];
    for (size_t i = 0; i < count; ++i) {
      // Insertion sort by key only: stable, so equal keys keep ascending triangle order.
      const Overlap item = tmp.buffer[i];
      size_t at = i;
      while (at > 0 && slice[at - 1].key > item.key) {
        slice[at] = slice[at - 1];
        --at;
      }
      slice[at] = item;
    }
  });

  report(0.9);
  // Pass 3: runs of equal keys -> voxels. Chunks start at run boundaries.
  const size_t chunkCount = std::max<size_t>(1, std::min<size_t>(overlapCount / 65536, 1024));
  std::vector<size_t> starts(chunkCount + 1, overlapCount);
  for (size_t c = 0; c < chunkCount; ++c) {
    size_t s = overlapCount * c / chunkCount;
    while (s > 0 && s < overlapCount && overlaps[s].key == overlaps[s - 1].key) ++s;
    starts[c] = s;
  }
  std::vector<size_t> runs(chunkCount, 0);
  base::parallelFor(chunkCount, 0, [&](uint64_t c) {
    size_t count = 0;
    for (size_t i = starts[c]; i < starts[c + 1]; ++i)
      count += i == starts[c] || overlaps[i].key != overlaps[i - 1].key;
    runs[c] = count;
  });
  std::vector<size_t> firstVoxel(chunkCount + 1, 0);
  for (size_t c = 0; c < chunkCount; ++c) firstVoxel[c + 1] = firstVoxel[c] + runs[c];
  result.voxels.resize(firstVoxel[chunkCount]);
  if (options.keepTriangleLists) {
    if (overlapCount > UINT32_MAX)
      return makeError(ErrorCode::kTooLarge, "surface voxelizer: ", overlapCount,
                       " voxel/triangle overlaps are more than a triangle list holds");
    result.triangleStart.assign(result.voxels.size() + 1, uint32_t(overlapCount));
    result.triangleIds.resize(overlapCount);
  }
  // One tally per worker that needs one (a histogram is 144 KB); fixed-point sums, so merging
  // them in any order gives the same bits.
  std::vector<std::unique_ptr<NormalErrorTally>> errors(workers);

  base::parallelFor(chunkCount, workers, [&](uint64_t c, unsigned worker) {
    if (options.computeNormalError && !errors[worker])
      errors[worker] = std::make_unique<NormalErrorTally>();
    NormalErrorTally* e = errors[worker].get();
    size_t out = firstVoxel[c];
    for (size_t begin = starts[c]; begin < starts[c + 1];) {
      size_t end = begin + 1;
      while (end < starts[c + 1] && overlaps[end].key == overlaps[begin].key) ++end;
      // Dominant triangle: largest area, then lowest index (the run is sorted by index).
      uint32_t dominant = overlaps[begin].triangle;
      double sum[3] = {0.0, 0.0, 0.0}, weights = 0.0;
      for (size_t i = begin; i < end; ++i) {
        const TriangleInfo& t = info[overlaps[i].triangle];
        if (t.area > info[dominant].area) dominant = overlaps[i].triangle;
        const double weight = options.normalRule == NormalRule::kAreaWeighted ? t.area : 1.0;
        for (int a = 0; a < 3; ++a) sum[a] += weight * t.normal[a];
        weights += weight;
      }
      std::array<float, 3> normal = info[dominant].normal;
      const double length = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
      if (options.normalRule != NormalRule::kLargestTriangle && length > 1e-6 * weights) {
        normal = {float(sum[0] / length), float(sum[1] / length), float(sum[2] / length)};
      }
      const auto xyz = voxelFromKey(overlaps[begin].key);
      const uint16_t material =
          mesh.triangleMaterials.empty() ? uint16_t(0) : mesh.triangleMaterials[dominant];
      if (options.keepTriangleLists) {
        result.triangleStart[out] = uint32_t(begin);
        for (size_t i = begin; i < end; ++i) result.triangleIds[i] = overlaps[i].triangle;
      }
      result.voxels[out++] = {xyz[0], xyz[1], xyz[2], normal, material};
      if (e != nullptr) {
        if (end - begin > 1) e->countMultiTriangleVoxel();
        for (size_t i = begin; i < end; ++i) {
          const auto& tn = info[overlaps[i].triangle].normal;
          const double cosine = std::clamp(
              double(normal[0]) * tn[0] + double(normal[1]) * tn[1] + double(normal[2]) * tn[2],
              -1.0, 1.0);
          const double degrees = std::acos(cosine) * (180.0 / 3.14159265358979323846);
          e->add(degrees);
        }
      }
      begin = end;
    }
  });

  report(1.0);
  if (options.computeNormalError) {
    auto tally = std::make_shared<NormalErrorTally>();
    for (const auto& e : errors)
      if (e) tally->merge(*e);
    result.normalError = tally->stats();
    result.normalTally = std::move(tally);
  }
  return result;
}

}  // namespace voxlink::geometry
