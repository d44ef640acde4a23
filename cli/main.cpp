// SPDX-License-Identifier: BSD-3-Clause
// voxlink: convert dense volumes to VoxLink files, report their footprint, validate them,
// render them.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <new>
#include <vector>

#include "base/output_file.h"
#include "cli/command.h"
#include "cli/printable_message.h"
#include "cli/process_ranks.h"
#include "geostat/blas_threads.h"

namespace voxlink::cli {

int reportError(const Error& error) {
  std::fprintf(stderr, "voxlink: %s\n", printableMessage(error.message).c_str());
  return exitStatusFor(error);
}

int exitStatusFor(const Error& error) {
  switch (error.code) {
    case ErrorCode::kInvalidArgument:
      return 2;
    case ErrorCode::kIo:
      return 3;
    default:
      return 1;
  }
}

int reportError(const Status& status) { return status ? 0 : reportError(status.error()); }

int reportOnRankZero(const Status& status) {
  if (status) return 0;
  return processRanks().rank() == 0 ? reportError(status) : exitStatusFor(status.error());
}

namespace {

// Output that could not be written (a closed pipe, a full disk behind a redirect) is an error:
// the exit status must not claim a report that nobody received.
int finishStandardOutput(int status) {
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    const int e = errno;
    std::fprintf(stderr, "voxlink: standard output: write failed: %s\n",
                 e ? std::strerror(e) : "I/O error");
    return status != 0 ? status : 3;
  }
  return status;
}

// The option parser's errors as one line and exit status 2 (CLI11 prints a second line and
// exits 104-112); --help and --version keep CLI11's output and status 0.
int reportParseError(CLI::App& app, const CLI::ParseError& e) {
  if (e.get_exit_code() == 0) return finishStandardOutput(app.exit(e));
  std::string what = e.what();
  for (char& c : what)
    if (c == '\n') c = ' ';
  if (processRanks().rank() == 0)  // every rank parsed the same line: one says it
    std::fprintf(stderr, "voxlink: %s (see voxlink --help)\n", printableMessage(what).c_str());
  return 2;
}

// A command that ran out of memory, or a library that threw where it should have returned an
// error: one line and status 1 instead of std::terminate's text and an abort, and no temporary
// output left behind (the registry knows them; unwinding to here has closed them).
int runCommand(const CommandRunner& run) {
  try {
    return run();
  } catch (const std::bad_alloc&) {
    base::removeRegisteredTemps();
    std::fprintf(stderr, "voxlink: out of memory\n");
  } catch (const std::exception& e) {
    base::removeRegisteredTemps();
    std::fprintf(stderr, "voxlink: internal error: %s\n", printableMessage(e.what()).c_str());
  }
  return 1;
}

}  // namespace

}  // namespace voxlink::cli

int main(int argc, char** argv) {
  using namespace voxlink::cli;
  // A core back for short jobs (geostat/blas_threads.h).
  voxlink::geostat::stopIdleBlasThreads();
  // MPI first (it may edit argv); MPI_Finalize when main returns, on every path.
  startProcessRanks(&argc, &argv);
  struct EndRanks {
    ~EndRanks() { endProcessRanks(); }
  } endRanks;
  CLI::App app{"VoxLink: sparse volumes as bricked per-voxel linked lists (Kauker et al. 2016)",
               "voxlink"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "voxlink 0.1.0");
  const CommandFactory factories[] = {
      addConvertCommand, addInfoCommand,        addValidateCommand, addSceneCommand,
      addStatsCommand,   addDicomCommand,       addKrigeCommand,    addGrfCommand,
      addExportCommand,  addPackCommand,        addUnpackCommand,
#ifdef VOXLINK_WITH_VIEWER
      addRenderCommand,  addBenchRenderCommand, addViewCommand,     addRenderExactCommand,
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
    return reportParseError(app, e);
  }
  voxlink::base::removeTempsOnSignals();
  for (auto& [sub, run] : commands) {
    if (!sub->parsed()) continue;
    // Only convert, scene build, krige and grf divide their work among MPI ranks; N copies of
    // another command would each do all of it.
    const std::string name = sub->get_name();
    if (processRanks().size() > 1 && name != "convert" && name != "scene" && name != "krige" &&
        name != "grf")
      return reportOnRankZero(voxlink::makeError(
          voxlink::ErrorCode::kInvalidArgument, "voxlink ", name,
          " runs in one process; of the commands only convert, scene build, krige and grf split "
          "their work "
          "across MPI ranks"));
    return finishStandardOutput(voxlink::cli::runCommand(run));
  }
  return 2;
}
