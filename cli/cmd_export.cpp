// SPDX-License-Identifier: BSD-3-Clause
// voxlink export FILE.vxl -o out.nrrd [--fill V] | -o out.vdb: the classified volume dense
// again in the source's type, or as OpenVDB grids of values and gradients (through the plugin).
#include <cstdio>

#include "base/file_name.h"
#include "base/output_file.h"
#include "base/parallel_for.h"
#include "cli/command.h"
#include "cli/output_options.h"
#include "cli/progress_bar.h"
#include "convert/vdb_export.h"
#include "format/validator.h"
#include "pack/open_file.h"
#include "report/dense_export.h"

namespace voxlink::cli {

CommandRunner addExportCommand(CLI::App& app) {
  struct Args {
    std::string path, output;
    double fill = 0;
    unsigned threads = 0;
    OutputOptions out;
  };
  auto args = std::make_shared<Args>();
  auto* cmd =
      app.add_subcommand("export", "Write a VoxLink file as dense NRRD or as OpenVDB grids");
  cmd->add_option("file", args->path, "VoxLink file (.vxl)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output,
                  "Output: .nrrd (dense, the source's type), .nhdr (the same as a detached header "
                  "and NAME.raw) or .vdb (values and gradient grids)")
      ->required();
  cmd->add_option("--fill", args->fill, "Value of removed voxels (must fit the source type)")
      ->check(finiteNumber())
      ->capture_default_str();
  addThreadsOption(cmd, args->threads);
  args->out.add(cmd, true);
  return [args] {
    const base::ThreadLimit limit(args->threads);  // every parallel path, OpenVDB's TBB too
    const std::string& out = args->output;
    const bool vdb = base::hasExtension(out, ".vdb");
    if (!vdb && !base::hasExtension(out, ".nrrd") && !base::hasExtension(out, ".nhdr"))
      return reportError(makeError(
          ErrorCode::kInvalidArgument, out,
          ": unknown export format; the output name must end in .nrrd, .nhdr (+ .raw) or .vdb"));
    if (Status s = base::checkOutputTarget(out, {args->path}); !s) return reportError(s);
    // Validating a quarter of the bar, exporting the rest.
    ProgressBar bar(args->out.showProgress());
    const base::ProgressCallback progress = bar.callback();
    auto file = pack::openFile(args->path);
    if (!file) return bar.fail(file.error());
    if (auto valid = format::validateFile(*file, base::progressPart(progress, 0, 0.25)); !valid)
      return bar.fail(valid.error());
    const base::ProgressCallback exportProgress = base::progressPart(progress, 0.25, 1);
    if (vdb) {
      auto written = convert::exportVdb(*file, out, exportProgress);
      bar.finish();
      if (!written) return reportError(written.error());
      args->out.print("%s: grids 'values' and 'gradient', %llu active voxels each, %.2f MB\n",
                      out.c_str(), (unsigned long long)written->voxels, written->bytes / 1e6);
      return 0;
    }
    auto summary = report::exportDenseNrrd(*file, out, args->fill, exportProgress);
    bar.finish();
    if (!summary) return reportError(summary.error());
    args->out.print("%s: %llu stored voxels, %llu filled with %g, %.2f MB dense NRRD%s\n",
                    out.c_str(), (unsigned long long)summary->keptVoxels,
                    (unsigned long long)summary->filledVoxels, args->fill, summary->bytes / 1e6,
                    base::hasExtension(out, ".nhdr") ? " (header + .raw)" : "");
    return 0;
  };
}

}  // namespace voxlink::cli
