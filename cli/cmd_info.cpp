// SPDX-License-Identifier: BSD-3-Clause
// voxlink info FILE [--json]: the memory footprint report (paper, Table 3) with the OpenVDB
// peer measured on the same voxels.
#include <cstdio>

#include "cli/command.h"
#include "cli/output_options.h"
#include "convert/vdb_footprint.h"
#include "format/validator.h"
#include "format/voxlink_file.h"
#include "pack/open_file.h"
#include "report/footprint.h"

namespace voxlink::cli {

CommandRunner addInfoCommand(CLI::App& app) {
  struct Args {
    std::string path;
    bool json = false;
    bool skipVdb = false;
    OutputOptions out;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("info", "Memory footprint report of a VoxLink file");
  cmd->add_option("file", args->path, "VoxLink file (.vxl)")->required()->check(CLI::ExistingFile);
  cmd->add_flag("--json", args->json, "Print the report as JSON");
  cmd->add_flag("--no-vdb", args->skipVdb,
                "Skip building the OpenVDB FloatGrid used for comparison");
  args->out.add(cmd, false);
  return [args] {
    auto file = pack::openValidatedFile(args->path);
    if (!file) return reportError(file.error());
    if (args->out.quiet) return 0;  // opened and validated: nothing else to say
    report::FootprintReport report = report::computeFootprint(*file);
    if (!args->skipVdb) {
      auto peer = convert::measureVdbFootprint(*file);
      if (!peer)
        return reportError(
            makeError(peer.code(), peer.message(), " (--no-vdb reports without it)"));
      report.peer = *peer;
    }
    std::fputs((args->json ? report::footprintJson(report) + "\n" : report::footprintTable(report))
                   .c_str(),
               stdout);
    return 0;
  };
}

}  // namespace voxlink::cli
