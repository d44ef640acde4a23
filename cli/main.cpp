// voxlink: convert dense volumes to VoxLink files, report their footprint, validate them,
// render them.
#include <cstdio>
#include <map>
#include <vector>

#include "cli/command.h"
#include "cli/printable_message.h"

namespace voxlink::cli {

int reportError(const Error& error) {
  std::fprintf(stderr, "voxlink: %s\n", printableMessage(error.message).c_str());
  switch (error.code) {
    case ErrorCode::kInvalidArgument: return 2;
    case ErrorCode::kIo: return 3;
    default: return 1;
  }
}

int reportError(const Status& status) { return status ? 0 : reportError(status.error()); }

}  // namespace voxlink::cli

int main(int argc, char** argv) {
  using namespace voxlink::cli;
  CLI::App app{"VoxLink: sparse volumes as bricked per-voxel linked lists (Kauker et al. 2016)",
               "voxlink"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "voxlink 0.1.0");
  const CommandFactory factories[] = {addConvertCommand, addInfoCommand, addValidateCommand, addSceneCommand, addStatsCommand, addKrigeCommand,
                                      addGrfCommand,
#ifdef VOXLINK_WITH_VIEWER
                                      addRenderCommand, addBenchRenderCommand, addViewCommand,
#endif
  };
  std::vector<std::pair<CLI::App*, CommandRunner>> commands;
  for (CommandFactory factory : factories) {
    const size_t before = app.get_subcommands({}).size();
    CommandRunner run = factory(app);
    commands.emplace_back(app.get_subcommands({}).at(before), std::move(run));
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  for (auto& [sub, run] : commands)
    if (sub->parsed()) return run();
  return 2;
}
