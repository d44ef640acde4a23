// voxlink export FILE.vxl -o out.nrrd [--fill V]: the classified volume dense again, in the
// source's type, for tools that read dense grids.
#include <cstdio>

#include "cli/command.h"
#include "format/dense_export.h"
#include "format/output_file.h"
#include "format/validator.h"

namespace voxlink::cli {

CommandRunner addExportCommand(CLI::App& app) {
  struct Args {
    std::string path, output;
    double fill = 0;
  };
  auto args = std::make_shared<Args>();
  auto* cmd =
      app.add_subcommand("export", "Write a VoxLink file's classified volume as dense NRRD");
  cmd->add_option("file", args->path, "VoxLink file (.vxl)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output, "Output (.nrrd: dense, the source's type)")
      ->required();
  cmd->add_option("--fill", args->fill, "Value of removed voxels (must fit the source type)")
      ->check(finiteNumber())
      ->capture_default_str();
  return [args] {
    const std::string& out = args->output;
    if (!out.ends_with(".nrrd"))
      return reportError(makeError(ErrorCode::kInvalidArgument, out,
                                   ": unknown export format; the output name must end in .nrrd"));
    if (Status s = format::checkOutputTarget(out, {args->path}); !s) return reportError(s);
    auto file = format::openValidatedFile(args->path);
    if (!file) return reportError(file.error());
    auto summary = format::exportDenseNrrd(*file, out, args->fill);
    if (!summary) return reportError(summary.error());
    std::printf("%s: %llu stored voxels, %llu filled with %g, %.2f MB dense NRRD\n", out.c_str(),
                (unsigned long long)summary->keptVoxels, (unsigned long long)summary->filledVoxels,
                args->fill, summary->bytes / 1e6);
    return 0;
  };
}

}  // namespace voxlink::cli
