// SPDX-License-Identifier: BSD-3-Clause
// `voxlink convert --batch LIST --out-dir DIR` in one process: one JSON line per file, a failed
// file reported while the others are converted, a summary, --resume, and outputs that are the
// bytes a single `voxlink convert` writes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

namespace fs = std::filesystem;

// A small u8 NRRD with a ball of bright voxels, so a threshold keeps some of it.
void writeBallNrrd(const std::string& path, uint32_t nx, uint32_t ny, uint32_t nz) {
  std::ostringstream header;
  header << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: " << nx << " " << ny << " " << nz
         << "\nencoding: raw\n\n";
  std::string bytes = header.str();
  for (uint32_t z = 0; z < nz; ++z)
    for (uint32_t y = 0; y < ny; ++y)
      for (uint32_t x = 0; x < nx; ++x) {
        const double dx = x - nx / 2.0, dy = y - ny / 2.0, dz = z - nz / 2.0;
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        bytes.push_back(static_cast<char>(r < nx / 3.0 ? 200 - int(r) : (x * 7 + y) % 50));
      }
  std::ofstream(path, std::ios::binary) << bytes;
}

std::vector<nlohmann::json> jsonLines(const std::string& text) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

TEST(CliBatch, ConvertsEveryFileReportsTheBadOneAndResumes) {
  TempDir dir;
  writeBallNrrd(dir.file("a.nrrd"), 40, 30, 20);
  writeBallNrrd(dir.file("b.nrrd"), 17, 33, 45);
  std::ofstream(dir.file("bad.nrrd")) << "NRRD0004\ntype: uint8\ndimension: 3\n";  // no sizes
  std::ofstream(dir.file("list.txt")) << "# scans\na.nrrd\n\nbad.nrrd\n"
                                      << dir.file("b.nrrd") << "\n";
  const std::string out = dir.file("converted");
  auto r = runVoxlink(
      {"convert", "--batch", dir.file("list.txt"), "--out-dir", out, "--threshold", "100"});
  EXPECT_EQ(r.status, 1) << r.err;  // one file failed
  auto lines = jsonLines(r.out);
  ASSERT_EQ(lines.size(), 4u) << r.out;
  int converted = 0, failed = 0;
  for (size_t i = 0; i + 1 < lines.size(); ++i) {
    const auto& j = lines[i];
    for (const char* key : {"input", "output", "status", "seconds", "rank"})
      EXPECT_TRUE(j.contains(key)) << key << " in " << j;
    if (j["status"] == "converted") {
      ++converted;
      EXPECT_GT(j["voxels"].get<uint64_t>(), 0u);
      EXPECT_GT(j["bytes_per_voxel"].get<double>(), 0.0);
      EXPECT_EQ(j["bytes"].get<uint64_t>(), fs::file_size(j["output"].get<std::string>()));
    } else {
      ++failed;
      EXPECT_EQ(j["status"], "failed");
      EXPECT_NE(j["error"].get<std::string>().find("bad.nrrd"), std::string::npos) << j;
    }
  }
  EXPECT_EQ(converted, 2);
  EXPECT_EQ(failed, 1);
  const auto& summary = lines.back()["summary"];
  EXPECT_EQ(summary["files"], 3);
  EXPECT_EQ(summary["converted"], 2);
  EXPECT_EQ(summary["failed"], 1);
  EXPECT_EQ(summary["ranks"], 1);
  EXPECT_FALSE(fs::exists(out + "/bad.vxl"));

  // The batch's outputs are the bytes of a single conversion.
  r = runVoxlink({"convert", dir.file("b.nrrd"), "--threshold", "100", "-o", dir.file("b.vxl")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(readBytes(dir.file("b.vxl")), readBytes(out + "/b.vxl"));

  // --resume skips the valid outputs and converts one that no longer validates.
  std::vector<uint8_t> damaged = readBytes(out + "/a.vxl");
  damaged[damaged.size() / 2] ^= 0x40;
  writeBytes(out + "/a.vxl", damaged);
  r = runVoxlink({"convert", "--batch", dir.file("list.txt"), "--out-dir", out, "--threshold",
                  "100", "--resume"});
  EXPECT_EQ(r.status, 1);
  lines = jsonLines(r.out);
  ASSERT_EQ(lines.size(), 4u) << r.out;
  for (size_t i = 0; i + 1 < lines.size(); ++i) {
    const std::string name = fs::path(lines[i]["input"].get<std::string>()).filename();
    const char* expected = name == "a.nrrd" ? "converted" : name == "b.nrrd" ? "skipped" : "failed";
    EXPECT_EQ(lines[i]["status"], expected) << lines[i];
  }
  EXPECT_EQ(lines.back()["summary"]["skipped"], 1);
  r = runVoxlink({"validate", out + "/a.vxl"});
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST(CliBatch, RefusesTwoInputsWithOneOutputAndAMissingInput) {
  TempDir dir;
  fs::create_directories(dir.file("x"));
  fs::create_directories(dir.file("y"));
  writeBallNrrd(dir.file("x/scan.nrrd"), 16, 16, 16);
  writeBallNrrd(dir.file("y/scan.nrrd"), 16, 16, 16);
  std::ofstream(dir.file("list.txt")) << "x/scan.nrrd\ny/scan.nrrd\n";
  auto r = runVoxlink({"convert", "--batch", dir.file("list.txt"), "--out-dir", dir.file("o"),
                       "--threshold", "100"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("list.txt:2: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("as line 1 does"), std::string::npos) << r.err;
  std::ofstream(dir.file("list.txt")) << "x/scan.nrrd\nnot-there.nrrd\n";
  r = runVoxlink({"convert", "--batch", dir.file("list.txt"), "--out-dir", dir.file("o"),
                  "--threshold", "100"});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("list.txt:2: "), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.file("o")));
  // Either a single input or a batch.
  r = runVoxlink({"convert", dir.file("x/scan.nrrd"), "--batch", dir.file("list.txt"), "--out-dir",
                  dir.file("o"), "--threshold", "100"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("give either INPUT -o OUTPUT"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace voxlink::testing
