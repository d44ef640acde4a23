// SPDX-License-Identifier: BSD-3-Clause
// The options every subcommand shares (docs/cli.md): each one `voxlink --help` lists accepts
// -q/--quiet, the commands that report progress accept --progress, and -q leaves stdout and
// stderr empty on success while errors still print.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

const std::string kHeadsq = std::string(VOXLINK_SAMPLES_DIR) + "/headsq/headsq.nrrd";

// The subcommand names under "Subcommands:" in a CLI11 help text.
std::vector<std::string> subcommandsIn(const std::string& help) {
  std::vector<std::string> names;
  std::istringstream in(help);
  std::string line;
  bool inSection = false;
  while (std::getline(in, line)) {
    if (line.rfind("SUBCOMMANDS:", 0) == 0 || line.rfind("Subcommands:", 0) == 0) {
      inSection = true;
      continue;
    }
    if (!inSection) continue;
    if (line.empty() || line[0] != ' ') break;
    std::istringstream words(line);
    std::string name;
    words >> name;
    if (!name.empty()) names.push_back(name);
  }
  return names;
}

// Every runnable command line prefix ("convert", "scene build", ...) and its help text.
void collectLeaves(const std::vector<std::string>& prefix,
                   std::vector<std::pair<std::string, std::string>>& leaves) {
  std::vector<std::string> args = prefix;
  args.push_back("--help");
  const CommandResult r = runVoxlink(args);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::string> children = subcommandsIn(r.out);
  if (children.empty() && !prefix.empty()) {
    std::string name;
    for (const std::string& word : prefix) name += (name.empty() ? "" : " ") + word;
    leaves.emplace_back(name, r.out);
  }
  for (const std::string& child : children) {
    std::vector<std::string> next = prefix;
    next.push_back(child);
    collectLeaves(next, leaves);
  }
}

TEST(CliVocabulary, EverySubcommandTakesQuietAndProgressWhereItReports) {
  std::vector<std::pair<std::string, std::string>> leaves;
  collectLeaves({}, leaves);
  std::set<std::string> names;
  for (const auto& [name, help] : leaves) names.insert(name);
  for (const char* expected : {"convert", "info", "validate", "export", "pack", "unpack", "stats",
                               "scene build", "dicom list", "krige", "grf"})
    EXPECT_TRUE(names.count(expected)) << expected << " missing from voxlink --help";
  // view: the progress of building a scene file before its window opens.
  const std::set<std::string> withProgress = {"convert", "stats",    "scene build", "krige",
                                              "grf",     "validate", "export",      "pack",
                                              "unpack",  "view"};
  for (const auto& [name, help] : leaves) {
    EXPECT_NE(help.find("-q,--quiet"), std::string::npos) << name << ":\n" << help;
    EXPECT_EQ(help.find("--progress") != std::string::npos, withProgress.count(name) == 1)
        << name << ":\n"
        << help;
  }
}

// Runs `args` and expects success with nothing at all on stdout or stderr.
void expectSilentSuccess(const std::vector<std::string>& args) {
  const CommandResult r = runVoxlink(args);
  std::string line;
  for (const std::string& a : args) line += a + " ";
  EXPECT_EQ(r.status, 0) << line << r.err;
  EXPECT_EQ(r.out, "") << line;
  EXPECT_EQ(r.err, "") << line;
}

TEST(CliVocabulary, QuietPrintsNothingOnSuccess) {
  TempDir dir;
  const std::string vxl = dir.file("headsq.vxl");
  expectSilentSuccess({"convert", kHeadsq, "--threshold", "1400", "-o", vxl, "-q"});
  ASSERT_TRUE(std::filesystem::exists(vxl));
  // -q wins over --progress: errors only.
  expectSilentSuccess({"convert", kHeadsq, "--threshold", "1400", "-o", dir.file("b.vxl"),
                       "--quiet", "--progress"});
  expectSilentSuccess({"info", vxl, "-q"});
  expectSilentSuccess({"validate", "-q", vxl});
  expectSilentSuccess({"stats", kHeadsq, "-q"});
  expectSilentSuccess({"export", vxl, "-o", dir.file("kept.nrrd"), "-q"});
  expectSilentSuccess({"pack", vxl, "-o", dir.file("p.vxl"), "-q"});
  expectSilentSuccess({"unpack", dir.file("p.vxl"), "-o", dir.file("u.vxl"), "-q"});
  expectSilentSuccess({"render", vxl, "-o", dir.file("h.png"), "--size", "32x32", "-q"});
  expectSilentSuccess({"grf", "--dims", "16,16,8", "-o", dir.file("f.nhdr"), "-q"});
  expectSilentSuccess({"scene", "build",
                       std::string(VOXLINK_SAMPLES_DIR) + "/scenes/house.scene.json",
                       "--resolution", "32", "-o", dir.file("house.vxl"), "-q"});
  EXPECT_TRUE(std::filesystem::exists(dir.file("kept.nrrd")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("u.vxl")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("f.nhdr")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("house.vxl")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("h.png")));
  // Without -q the same commands report (so the silence above is -q's doing).
  const CommandResult loud = runVoxlink({"validate", vxl});
  EXPECT_EQ(loud.status, 0);
  EXPECT_NE(loud.out.find(": ok"), std::string::npos) << loud.out;
}

TEST(CliVocabulary, QuietStillReportsErrors) {
  TempDir dir;
  const std::string bad = dir.file("bad.vxl");
  std::ofstream(bad) << "not a voxlink file";
  for (const char* command : {"info", "validate"}) {
    const CommandResult r = runVoxlink({command, "-q", bad});
    EXPECT_NE(r.status, 0) << command;
    EXPECT_NE(r.err.find("bad.vxl"), std::string::npos) << command << ": " << r.err;
    EXPECT_EQ(r.out, "") << command;
  }
}

TEST(CliVocabulary, ProgressDrawsTheBarWhenStderrIsAFile) {
  TempDir dir;
  const CommandResult convert = runVoxlink(
      {"convert", kHeadsq, "--threshold", "1400", "-o", dir.file("h.vxl"), "--progress"});
  ASSERT_EQ(convert.status, 0) << convert.err;
  EXPECT_NE(convert.err.find("100.0%"), std::string::npos) << convert.err;
  const CommandResult plain =
      runVoxlink({"convert", kHeadsq, "--threshold", "1400", "-o", dir.file("i.vxl")});
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_EQ(plain.err, "");  // not a terminal: no bar unless asked
  const CommandResult stats = runVoxlink({"stats", kHeadsq, "--progress"});
  ASSERT_EQ(stats.status, 0) << stats.err;
  EXPECT_NE(stats.err.find("histogram"), std::string::npos) << stats.err;
  EXPECT_NE(stats.err.find("100.0%"), std::string::npos) << stats.err;
  const CommandResult grf = runVoxlink({"grf", "--dims", "16,16,8", "--progress"});
  ASSERT_EQ(grf.status, 0) << grf.err;
  EXPECT_NE(grf.err.find("field"), std::string::npos) << grf.err;
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// validate, export (NRRD, NHDR, VDB), pack and unpack draw a bar that reaches 100 % with
// --progress on a real file, nothing without it (stderr is not a terminal here) or with -q, and
// write the same bytes either way.
TEST(CliVocabulary, FileCommandsDrawTheBarWithProgress) {
  TempDir dir;
  const std::string vxl = dir.file("h.vxl");
  ASSERT_EQ(runVoxlink({"convert", kHeadsq, "--threshold", "1400", "-o", vxl, "-q"}).status, 0);
  struct Case {
    std::vector<std::string> args;  // without the output name
    std::string output, stage;
  };
  const std::vector<Case> cases = {
      {{"validate", vxl}, "", "bricks"},
      {{"export", vxl, "-o"}, "e.nrrd", "exporting"},
      {{"export", vxl, "-o"}, "e.nhdr", "exporting"},
      {{"export", vxl, "-o"}, "e.vdb", "grids"},
      {{"pack", vxl, "-o"}, "p.vxl", "packing"},
      {{"unpack", dir.file("plain-p.vxl"), "-o"}, "u.vxl", "unpacking"},
  };
  for (const Case& c : cases) {
    std::string line;
    for (const std::string& a : c.args) line += a + " ";
    auto run = [&](const std::string& prefix, const std::vector<std::string>& extra) {
      std::vector<std::string> args = c.args;
      if (!c.output.empty()) args.push_back(dir.file(prefix + c.output));
      args.insert(args.end(), extra.begin(), extra.end());
      return runVoxlink(args);
    };
    const CommandResult plain = run("plain-", {});
    ASSERT_EQ(plain.status, 0) << line << plain.err;
    EXPECT_EQ(plain.err, "") << line;  // not a terminal: no bar unless asked
    const CommandResult bar = run("bar-", {"--progress"});
    ASSERT_EQ(bar.status, 0) << line << bar.err;
    EXPECT_NE(bar.err.find("100.0%"), std::string::npos) << line << bar.err;
    EXPECT_NE(bar.err.find(c.stage), std::string::npos) << line << bar.err;
    EXPECT_NE(bar.out, "") << line;  // the report still printed
    const CommandResult quiet = run("quiet-", {"-q", "--progress"});
    ASSERT_EQ(quiet.status, 0) << line << quiet.err;
    EXPECT_EQ(quiet.out, "") << line;
    EXPECT_EQ(quiet.err, "") << line;
    // The VDB archive holds a random UUID, a .nhdr names its .raw; every other output (and the
    // .raw) is the same bytes.
    const std::string same = c.output == "e.nhdr" ? "e.raw" : c.output;
    if (!same.empty() && same != "e.vdb") {
      EXPECT_EQ(readBytes(dir.file("bar-" + same)), readBytes(dir.file("plain-" + same))) << line;
    }
  }
}

}  // namespace
}  // namespace voxlink::testing
