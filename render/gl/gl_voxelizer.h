// SPDX-License-Identifier: BSD-3-Clause
// The paper's GL surface voxelization (sections 3.1.1 and 4.1), headless on any GL 4.5 context
// (llvmpipe included). Each non-degenerate triangle is rasterized once, in the orthographic view
// along its dominant normal axis (the per-triangle swizzle: three draws, one per axis, depth test
// off, no attachments); every fragment is appended to its (u, v) column's list with an atomic
// counter and an atomic head exchange (shaders/gl_voxelize.*.glsl). The host reads the lists
// back, sorts each by depth, and resolves the (voxel, triangle) pairs with the exact path's rules
// (geometry/fragment_resolve.h), so both paths store the same kind of fragment.
//
// Two coverages (GlCoverage). kCenter is the paper's: one voxel per covered pixel centre, at the
// depth there, so the voxels are (up to float rounding at voxel faces) a subset of the exact
// path's, and a thin one: slivers that cover no pixel centre and the second voxel where a tilted
// surface crosses a voxel layer inside a column are missed. kConservative emulates conservative
// rasterization (llvmpipe has none) and marks every voxel of the column that the triangle's part
// over the pixel reaches: the exact path's voxels up to float rounding.
// geometry/voxel_set_compare.h measures both.
#pragma once

#include <epoxy/gl.h>

#include <cstdint>

#include "base/error.h"
#include "geometry/surface_voxelizer.h"
#include "geometry/triangle_mesh.h"
#include "geometry/voxel_grid.h"

namespace voxlink::render::gl {

enum class GlCoverage { kCenter, kConservative };

struct GlVoxelizeOptions {
  GlCoverage coverage = GlCoverage::kConservative;
  geometry::SurfaceVoxelizeOptions resolve;  // normal rule and statistics, as the exact path
  // Expected fragments per batch of triangles (0: half the largest storage buffer, at most 64
  // MiB of fragments); smaller batches bound GPU memory for any mesh size.
  uint64_t batchFragments = 0;
};

struct GlVoxelizeStats {
  uint64_t fragments = 0;          // appended by the fragment stage
  uint64_t zeroAreaTriangles = 0;  // not drawn
  int draws = 0;                   // passes of three draws (more than 1 when the buffer grew)
  double rasterSeconds = 0;        // upload, draws and finish
  double readbackSeconds = 0;      // lists back to the host
  double resolveSeconds = 0;       // depth sort and one fragment per voxel
};

struct GlSurfaceVoxelization {
  geometry::SurfaceVoxelization surface;  // voxels sorted by (z, y, x), as the exact path
  GlVoxelizeStats stats;
};

class GlSurfaceVoxelizer {
 public:
  // Needs a current GL 4.3+ context (createHeadlessContext); compiles the programs once.
  static Result<GlSurfaceVoxelizer> create();
  GlSurfaceVoxelizer(GlSurfaceVoxelizer&& other) noexcept;
  GlSurfaceVoxelizer& operator=(GlSurfaceVoxelizer&& other) noexcept;
  GlSurfaceVoxelizer(const GlSurfaceVoxelizer&) = delete;
  GlSurfaceVoxelizer& operator=(const GlSurfaceVoxelizer&) = delete;
  ~GlSurfaceVoxelizer();

  // Errors: as voxelizeSurface for the mesh and grid; a grid wider than the largest viewport or
  // framebuffer; heads or fragments beyond the largest storage buffer.
  Result<GlSurfaceVoxelization> voxelize(const geometry::TriangleMesh& mesh,
                                         const geometry::VoxelGrid& grid,
                                         const GlVoxelizeOptions& options = {});

 private:
  GlSurfaceVoxelizer() = default;
  GLuint program_ = 0;
  GLuint vertexArray_ = 0;
  GLuint framebuffer_ = 0;
};

}  // namespace voxlink::render::gl
