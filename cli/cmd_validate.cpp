// SPDX-License-Identifier: BSD-3-Clause
// voxlink validate FILE...: every checksum and structural invariant.
#include <cstdio>

#include "cli/command.h"
#include "cli/output_options.h"
#include "cli/progress_bar.h"
#include "format/validator.h"
#include "format/voxlink_file.h"
#include "pack/open_file.h"

namespace voxlink::cli {

CommandRunner addValidateCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("validate",
                                 "Check every checksum and structural invariant of VoxLink files");
  auto files = std::make_shared<std::vector<std::string>>();
  auto out = std::make_shared<OutputOptions>();
  cmd->add_option("files", *files, "VoxLink files (.vxl)")->required()->check(CLI::ExistingFile);
  out->add(cmd, true);
  return [files, out] {
    int status = 0;
    for (const std::string& path : *files) {
      auto file = pack::openFile(path);
      if (!file) {
        status = reportError(file.error());
        continue;
      }
      ProgressBar bar(out->showProgress());
      auto report = format::validateFile(*file, bar.callback());
      bar.finish();
      if (!report) {
        status = reportError(report.error());
        continue;
      }
      out->print("%s: ok (%llu bytes checksummed, %llu bricks, %llu voxels)\n", path.c_str(),
                 (unsigned long long)report->bytesChecked,
                 (unsigned long long)report->bricksChecked,
                 (unsigned long long)report->voxelsChecked);
    }
    return status;
  };
}

}  // namespace voxlink::cli
