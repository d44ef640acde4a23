// SPDX-License-Identifier: BSD-3-Clause
// voxlink scene build SCENE.json -o OUT.vxl: meshes, spheres and a volume voxelized into one
// VoxLink buffer (docs/scene.md); under mpirun split across ranks (docs/scale.md).
#include <cstdio>
#include <memory>
#include <optional>

#include "base/output_file.h"
#include "base/parallel_for.h"
#include "cli/command.h"
#include "cli/output_options.h"
#include "cli/process_ranks.h"
#include "cli/progress_bar.h"
#include "format/bricked_volume.h"
#include "format/surface_mode.h"
#include "geometry/fragment_planes.h"
#include "scene/scene_assembly.h"
#include "scene/scene_description.h"
#include "scene/scene_input_files.h"
#ifdef VOXLINK_WITH_VIEWER
#include "render/gl/gl_context.h"
#include "render/gl/gl_voxelizer.h"
#endif

namespace voxlink::cli {

CommandRunner addSceneCommand(CLI::App& app) {
  auto* scene =
      app.add_subcommand("scene", "Build VoxLink scenes from meshes, spheres and volumes");
  scene->require_subcommand(1);
  auto* build = scene->add_subcommand(
      "build", "Voxelize a scene file's objects into one .vxl (docs/scene.md)");
  struct Options {
    std::string input, output;
    uint32_t resolution = 0, brick = 0;
    unsigned threads = 0;
    OutputOptions out;
    std::string voxelizer = "exact";
    std::string surface = "mean";
    double fragmentAngle = geometry::kDefaultMergeAngleDegrees;
  };
  auto o = std::make_shared<Options>();
  build->add_option("scene", o->input, "scene file (JSON)")->required();
  build->add_option("-o,--output", o->output, "output .vxl")->required();
  build
      ->add_option("--resolution", o->resolution,
                   "voxels along the scene's longest axis (overrides grid.resolution; ignored with "
                   "a volume)")
      ->check(CLI::Range(2u, 65536u));
  build->add_option("--brick", o->brick, "brick edge 4, 8, 16 or 32 (overrides grid.brick)")
      ->check(CLI::IsMember({4u, 8u, 16u, 32u}));
  build
      ->add_option("--voxelizer", o->voxelizer,
                   "mesh voxelizer: exact (CPU, every overlapped voxel) or gl (the paper's "
                   "rasterization, headless; may miss sliver voxels, docs/geometry.md)")
      ->check(CLI::IsMember({"exact", "gl"}));
  build
      ->add_option("--surface", o->surface,
                   "what a surface voxel keeps: mean (one fragment, version 2.0 files), planes "
                   "(a list of planes merged by --fragment-angle) or triangles (references to "
                   "the triangles, stored in the file); docs/format.md")
      ->check(CLI::IsMember(std::vector<std::string>(format::kSurfaceModeNames.begin(),
                                                     format::kSurfaceModeNames.end())));
  build
      ->add_option("--fragment-angle", o->fragmentAngle,
                   "planes: triangles of a voxel share a fragment when their normals differ by "
                   "at most this many degrees")
      ->check(CLI::Range(0.0, 180.0));
  addThreadsOption(build, o->threads);
  o->out.add(build, true);
  return [o, build] {
    if (!build->parsed()) return 2;
    const base::ThreadLimit limit(o->threads);  // every parallel path, for the whole build
    // On several MPI ranks every rank reads the scene file and checks the target itself; the
    // errors are agreed, so no rank is left waiting for one that stopped.
    base::RankGroup& ranks = processRanks();
    const bool root = ranks.rank() == 0;
    auto description = scene::readSceneDescription(o->input);
    Status ready = description.status();
    if (ready)
      ready = base::checkOutputTarget(o->output, o->input, scene::sceneInputFiles(*description));
    if (ready && ranks.size() > 1 && o->voxelizer == "gl")
      ready = makeError(ErrorCode::kUnsupported,
                        "--voxelizer gl runs in one process; use --voxelizer exact on several MPI "
                        "ranks");
    if (Status all = base::agree(ranks, ready); !all) return reportOnRankZero(all);
    if (o->resolution) description->grid.resolution = o->resolution;
    if (o->brick) description->grid.brickSize = o->brick;
    description->grid.surface = *format::parseSurfaceMode(o->surface);
    description->grid.fragmentAngleDegrees = o->fragmentAngle;
    if (o->voxelizer == "gl" && description->grid.surface != format::SurfaceMode::kMean)
      return reportOnRankZero(
          makeError(ErrorCode::kUnsupported,
                    "--voxelizer gl keeps one fragment per voxel; use --voxelizer "
                    "exact with --surface ",
                    o->surface));
    scene::SurfaceVoxelizer voxelizer;  // empty: the exact CPU path
#ifdef VOXLINK_WITH_VIEWER
    std::unique_ptr<render::gl::GlContext> context;
    std::optional<render::gl::GlSurfaceVoxelizer> gl;
    if (o->voxelizer == "gl") {
      auto created = render::gl::createHeadlessContext();
      if (!created) return reportError(created.error());
      context = std::move(*created);
      auto program = render::gl::GlSurfaceVoxelizer::create();
      if (!program) return reportError(program.error());
      gl.emplace(std::move(*program));
      // GL draws in one go: its progress is the stage's start and end only.
      voxelizer = [&gl](
                      const geometry::TriangleMesh& mesh, const geometry::VoxelGrid& grid,
                      const std::function<void(double)>&) -> Result<geometry::SurfaceVoxelization> {
        VOXLINK_ASSIGN_OR_RETURN(render::gl::GlSurfaceVoxelization r, gl->voxelize(mesh, grid));
        return std::move(r.surface);
      };
    }
#else
    if (o->voxelizer == "gl")
      return reportError(makeError(ErrorCode::kUnsupported,
                                   "--voxelizer gl: this voxlink was built without the viewer"));
#endif
    ProgressBar bar(root && o->out.showProgress());
    auto built = scene::buildScene(
        *description, [&](const char* stage, double f) { bar.update(f, stage); }, voxelizer,
        &ranks);
    if (!built) return reportOnRankZero(built.status());
    bar.update(1.0, "write");
    // Rank 0 holds the merged voxels and writes the file (a temporary renamed into place).
    Status written = root ? format::writeBrickedVolume(o->output, built->volume) : Status::ok();
    bar.finish();
    if (Status all = base::agree(ranks, written); !all) return reportOnRankZero(all);
    if (!root) return 0;
    const scene::SceneBuildReport& r = built->report;
    o->out.print(
        "%s: %ux%ux%u [%u], %llu voxels (%llu surface from %llu triangles, %llu sphere from %llu "
        "spheres, "
        "%llu volume), %llu materials; normal error mean %.2f / p95 %.2f / max %.2f deg; "
        "load %.2f s, voxelize %.2f s (%s), merge %.2f s\n",
        o->output.c_str(), r.dims[0], r.dims[1], r.dims[2], built->volume.description.brickSize,
        (unsigned long long)built->volume.voxelCount(), (unsigned long long)r.surfaceVoxels,
        (unsigned long long)r.triangles, (unsigned long long)r.sphereVoxels,
        (unsigned long long)r.spheres, (unsigned long long)r.volumeVoxels,
        (unsigned long long)r.materials, r.normalError.meanDegrees, r.normalError.p95Degrees,
        r.normalError.maxDegrees, r.loadSeconds, r.voxelizeSeconds, o->voxelizer.c_str(),
        r.mergeSeconds);
    if (r.surfaceMode == format::SurfaceMode::kPlanes)
      o->out.print(
          "%s: planes: %llu fragments (%.3f per surface voxel, merged within %.1f deg; %llu "
          "voxel/triangle pairs under %.2f of a voxel face given no plane, not in the normal "
          "error); plane offsets rounded by at most %.2e voxel\n",
          o->output.c_str(), (unsigned long long)r.fragments,
          r.surfaceVoxels ? double(r.fragments) / double(r.surfaceVoxels) : 0.0, o->fragmentAngle,
          (unsigned long long)r.planePairsLeftOut, geometry::kMinFragmentArea,
          r.maxPlaneOffsetError);
    if (r.surfaceMode == format::SurfaceMode::kTriangles)
      o->out.print("%s: triangles: %llu references (%.3f per surface voxel) to %llu triangles\n",
                   o->output.c_str(), (unsigned long long)r.fragments,
                   r.surfaceVoxels ? double(r.fragments) / double(r.surfaceVoxels) : 0.0,
                   (unsigned long long)r.triangles);
    return std::fflush(stdout) == 0 && !std::ferror(stdout)
               ? 0
               : reportError(makeError(ErrorCode::kIo, "stdout: write failed"));
  };
}

}  // namespace voxlink::cli
