// SPDX-License-Identifier: BSD-3-Clause
// Surface voxelization benchmark (docs/geometry.md): the exact CPU voxelizer of geometry/ and the
// GL voxelizer (render/gl/gl_voxelizer.h, headless) against OpenVDB's
// tools::meshToUnsignedDistanceField (tools::meshToVolume with an unsigned band) with a
// half-width of 1 voxel (what a user would pick to get a surface band), on the same mesh and grid
// in the same run, same threads (TBB).
//   voxlink_voxelize_bench [DATA_DIR] [RUNS]
// Prints tables: load time, voxelization time of both paths (median of RUNS, default 3), surface
// voxels, what the GL path misses or adds against the exact one, occupied bricks, bytes per voxel
// and MB of the written version 2 file for bricks of 8 and 16 (the paper's Table 1 columns),
// what the single kept normal costs, and the peer.
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "format/bricked_volume.h"
#include "geometry/mesh_loader.h"
#include "geometry/surface_voxelizer.h"
#include "geometry/voxel_set_compare.h"
#include "render/gl/gl_context.h"
#include "render/gl/gl_voxelizer.h"
#include "scene/scene_assembly.h"

namespace {

using namespace voxlink::geometry;
using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

double cpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Percentage of bricks of n^3 voxels that hold at least one voxel.
double occupiedBricks(const std::vector<SurfaceVoxel>& voxels, const VoxelGrid& grid, uint32_t n) {
  std::vector<uint64_t> keys;
  keys.reserve(voxels.size());
  for (const SurfaceVoxel& v : voxels) keys.push_back(voxelKey(v.x / n, v.y / n, v.z / n));
  std::sort(keys.begin(), keys.end());
  const double occupied = double(std::unique(keys.begin(), keys.end()) - keys.begin());
  double total = 1.0;
  for (uint32_t d : grid.dims) total *= double((d + n - 1) / n);
  return 100.0 * occupied / total;
}

// Bytes of the version 2 file `voxlink scene build` writes for the mesh alone (exact path).
uint64_t sceneFileBytes(const std::string& meshPath, uint32_t resolution, uint32_t brick,
                        uint64_t* voxels) {
  voxlink::scene::SceneDescription d;
  d.path = "bench";
  d.grid.resolution = resolution;
  d.grid.brickSize = brick;
  voxlink::scene::SceneObject o;
  o.path = meshPath;
  d.objects.push_back(o);
  auto built = voxlink::scene::buildScene(d);
  if (!built) {
    std::fprintf(stderr, "%s\n", built.message().c_str());
    std::exit(1);
  }
  const auto file = std::filesystem::temp_directory_path() /
                    ("voxlink-voxelize-bench-" + std::to_string(::getpid()) + ".vxl");
  if (auto s = voxlink::format::writeBrickedVolume(file.string(), built->volume); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    std::exit(1);
  }
  *voxels = built->volume.voxelCount();
  const uint64_t bytes = std::filesystem::file_size(file);
  std::filesystem::remove(file);
  return bytes;
}

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dataDir = argc > 1 ? argv[1] : VOXLINK_BENCH_DATA_DIR;
  const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  openvdb::initialize();
  auto context = voxlink::render::gl::createHeadlessContext();
  if (!context) {
    std::fprintf(stderr, "%s\n", context.message().c_str());
    return 1;
  }
  auto glVoxelizer = voxlink::render::gl::GlSurfaceVoxelizer::create();
  if (!glVoxelizer) {
    std::fprintf(stderr, "%s\n", glVoxelizer.message().c_str());
    return 1;
  }
  struct Input {
    const char* name;
    const char* path;
  };
  const Input inputs[] = {{"bunny", "mesh/vtk_bunny.ply"},
                          {"bunny.obj", "mesh/c3dtm_stanford-bunny.obj"},
                          {"horse", "mesh/vtk_horse.ply"},
                          {"dragon", "mesh/stanford_dragon_decimated.ply"}};
  std::printf("hardware threads %u, load average at start %s, runs %d (median), GL: %s\n",
              std::thread::hardware_concurrency(), loadAverage().c_str(), runs,
              (*context)->description().c_str());
  std::printf(
      "voxlink: exact SAT surface voxels, normal error off while timed; "
      "vdb: meshToUnsignedDistanceField, half-width 1 voxel\n\n");
  std::printf("%-9s %9s %5s %8s %8s %8s %10s %7s %7s %22s %8s %10s %6s\n", "mesh", "triangles",
              "res", "load s", "vox s", "vox cpu", "voxels", "b8 %", "b16 %",
              "normal err mean/p95/max", "vdb s", "vdb active", "vdb/vx");
  struct RuleRow {
    std::string mesh;
    NormalErrorStats stats[3];
  };
  std::vector<RuleRow> ruleRows;
  std::vector<std::string> glRows, footprintRows;
  for (const Input& input : inputs) {
    const std::string path = dataDir + "/" + input.path;
    std::vector<double> loadTimes;
    TriangleMesh mesh;
    for (int r = 0; r < runs; ++r) {
      const auto t0 = Clock::now();
      auto loaded = loadMesh(path);
      loadTimes.push_back(seconds(t0, Clock::now()));
      if (!loaded) {
        std::fprintf(stderr, "%s\n", loaded.message().c_str());
        return 1;
      }
      mesh = std::move(loaded).value();
    }
    const bool onlyLoad = std::string(input.name) == "bunny.obj";  // the OBJ: load time only
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
    for (size_t v = 0; v < mesh.vertexCount(); ++v)
      points.emplace_back(mesh.positions[3 * v], mesh.positions[3 * v + 1],
                          mesh.positions[3 * v + 2]);
    for (size_t t = 0; t < mesh.triangleCount(); ++t)
      triangles.emplace_back(mesh.triangles[3 * t], mesh.triangles[3 * t + 1],
                             mesh.triangles[3 * t + 2]);
    for (uint32_t resolution : {256u, 512u, 1024u}) {
      if (onlyLoad) {
        std::printf("%-9s %9zu %5s %8.3f   (load only)\n", input.name, mesh.triangleCount(), "-",
                    median(loadTimes));
        break;
      }
      const VoxelGrid grid = fitGrid(meshBounds(mesh), resolution).value();
      SurfaceVoxelizeOptions timed;
      timed.computeNormalError = false;
      std::vector<double> wall, cpu;
      size_t voxelCount = 0;
      for (int r = 0; r < runs; ++r) {
        const double c0 = cpuSeconds();
        const auto t0 = Clock::now();
        auto result = voxelizeSurface(mesh, grid, timed);
        wall.push_back(seconds(t0, Clock::now()));
        cpu.push_back(cpuSeconds() - c0);
        if (!result) {
          std::fprintf(stderr, "%s\n", result.message().c_str());
          return 1;
        }
        voxelCount = result->voxels.size();
      }
      const SurfaceVoxelization full = voxelizeSurface(mesh, grid).value();
      const NormalErrorStats& e = full.normalError;
      // The peer: index space with voxel centres at origin + index * spacing, as ours.
      auto xform = openvdb::math::Transform::createLinearTransform(grid.spacing);
      xform->postTranslate(openvdb::Vec3d(grid.origin[0], grid.origin[1], grid.origin[2]));
      std::vector<double> vdbWall;
      uint64_t vdbActive = 0;
      for (int r = 0; r < runs; ++r) {
        const auto t0 = Clock::now();
        auto vdb = openvdb::tools::meshToUnsignedDistanceField<openvdb::FloatGrid>(
            *xform, points, triangles, std::vector<openvdb::Vec4I>(), 1.0f);
        vdbWall.push_back(seconds(t0, Clock::now()));
        vdbActive = vdb->activeVoxelCount();
      }
      // The GL path: the whole call (upload, three draws, read-back, depth sort, resolve), with
      // the paper's pixel-centre coverage and with emulated conservative rasterization.
      char line[320];
      for (const auto coverage : {voxlink::render::gl::GlCoverage::kCenter,
                                  voxlink::render::gl::GlCoverage::kConservative}) {
        const char* coverageName =
            coverage == voxlink::render::gl::GlCoverage::kCenter ? "centre" : "cons.";
        std::vector<double> glWall, glRaster, glCpu;
        voxlink::render::gl::GlSurfaceVoxelization gl;
        voxlink::render::gl::GlVoxelizeOptions glOptions;
        glOptions.resolve = timed;
        glOptions.coverage = coverage;
        for (int r = 0; r < runs; ++r) {
          const double c0 = cpuSeconds();
          const auto t0 = Clock::now();
          auto result = glVoxelizer->voxelize(mesh, grid, glOptions);
          glWall.push_back(seconds(t0, Clock::now()));
          glCpu.push_back(cpuSeconds() - c0);
          if (!result) {
            std::fprintf(stderr, "%s\n", result.message().c_str());
            return 1;
          }
          glRaster.push_back(result->stats.rasterSeconds);
          gl = std::move(result).value();
        }
        const VoxelSetComparison cmp = compareSurfaceVoxels(full.voxels, gl.surface.voxels);
        char normal[64];
        std::snprintf(normal, sizeof normal, "%.2f/%.2f/%.1f", cmp.normalMeanDegrees,
                      cmp.normalP95Degrees, cmp.normalMaxDegrees);
        std::snprintf(line, sizeof line,
                      "%-9s %-6s %5u %8.3f %8.3f %7.1f %9.3f %8.3f %10zu %10zu %9llu %7.3f %7llu "
                      "%16s",
                      input.name, coverageName, resolution, median(wall), median(glWall),
                      1.0 / median(glWall), median(glRaster), median(glCpu), full.voxels.size(),
                      gl.surface.voxels.size(), (unsigned long long)cmp.missing,
                      100.0 * double(cmp.missing) / double(std::max<uint64_t>(1, cmp.reference)),
                      (unsigned long long)cmp.extra, normal);
        glRows.push_back(line);
      }
      for (uint32_t brick : {8u, 16u}) {
        uint64_t stored = 0;
        const uint64_t bytes = sceneFileBytes(path, resolution, brick, &stored);
        std::snprintf(line, sizeof line, "%-9s %5u %5u %10llu %7.2f %8.2f %9.2f", input.name,
                      resolution, brick, (unsigned long long)stored,
                      occupiedBricks(full.voxels, grid, brick),
                      double(bytes) / double(std::max<uint64_t>(1, stored)), double(bytes) / 1e6);
        footprintRows.push_back(line);
      }
      char errors[64];
      std::snprintf(errors, sizeof errors, "%.2f/%.2f/%.1f", e.meanDegrees, e.p95Degrees,
                    e.maxDegrees);
      std::printf("%-9s %9zu %5u %8.3f %8.3f %8.3f %10zu %7.2f %7.2f %22s %8.3f %10llu %6.2f\n",
                  input.name, mesh.triangleCount(), resolution, median(loadTimes), median(wall),
                  median(cpu), voxelCount, occupiedBricks(full.voxels, grid, 8),
                  occupiedBricks(full.voxels, grid, 16), errors, median(vdbWall),
                  (unsigned long long)vdbActive, median(vdbWall) / median(wall));
      if (resolution == 512) {
        RuleRow row{input.name, {}};
        const NormalRule rules[3] = {NormalRule::kAreaWeighted, NormalRule::kUnweighted,
                                     NormalRule::kLargestTriangle};
        for (int i = 0; i < 3; ++i) {
          SurfaceVoxelizeOptions options;
          options.normalRule = rules[i];
          row.stats[i] = voxelizeSurface(mesh, grid, options).value().normalError;
        }
        ruleRows.push_back(row);
      }
    }
  }
  std::printf(
      "%-9s %9d %5d %8s %8.3f %8s   (published: cuda_voxelizer CPU, 12 threads of an "
      "i7-8750H; not measured here)\n",
      "bunny ref", 69451, 256, "-", 0.118, "-");
  std::printf("%-9s %9d %5d %8s %8.3f\n", "bunny ref", 69451, 512, "-", 0.309);
  std::printf("%-9s %9d %5d %8s %8.3f\n", "bunny ref", 69451, 1024, "-", 1.048);
  std::printf(
      "\nGL path (%s) against the exact path: times are medians of the whole call; fps = 1 / "
      "gl s; raster = upload + draws + finish; gl cpu = CPU seconds of the process in the call "
      "(llvmpipe's threads included); normal = angle between the two paths' normals on "
      "common voxels, mean/p95/max degrees\n",
      (*context)->description().c_str());
  std::printf("%-9s %-6s %5s %8s %8s %7s %9s %8s %10s %10s %9s %7s %7s %16s\n", "mesh", "cover",
              "res", "exact s", "gl s", "gl fps", "raster s", "gl cpu", "exact vx", "gl vx",
              "missed", "miss %", "added", "normal");
  for (const std::string& row : glRows) std::printf("%s\n", row.c_str());
  std::printf(
      "\nfootprint of the written version 2 file (voxlink scene build, exact path; the paper's "
      "Table 1 columns; MB = 10^6 bytes)\n");
  std::printf("%-9s %5s %5s %10s %7s %8s %9s\n", "mesh", "res", "brick", "voxels", "bricks %",
              "B/voxel", "MB");
  for (const std::string& row : footprintRows) std::printf("%s\n", row.c_str());
  std::printf(
      "\nnormal rule at 512: angle between the kept normal and each overlapping "
      "triangle's normal, mean/p95/max degrees\n");
  std::printf("%-9s %22s %22s %22s\n", "mesh", "area-weighted", "unweighted", "largest triangle");
  for (const RuleRow& row : ruleRows) {
    std::printf("%-9s", row.mesh.c_str());
    for (const NormalErrorStats& s : row.stats) {
      char cell[64];
      std::snprintf(cell, sizeof cell, "%.2f/%.2f/%.1f", s.meanDegrees, s.p95Degrees, s.maxDegrees);
      std::printf(" %22s", cell);
    }
    std::printf("\n");
  }
  std::printf("load average at end %s\n", loadAverage().c_str());
  return 0;
}
