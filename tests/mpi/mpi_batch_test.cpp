// SPDX-License-Identifier: BSD-3-Clause
// `mpirun -n 3 voxlink convert --batch LIST --out-dir DIR`: every file converted once by some
// rank, to the bytes one process writes; a bad file reported, the others converted.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "tests/mpi/mpi_launch.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

namespace fs = std::filesystem;

void writeNrrd(const std::string& path, uint32_t n, uint8_t seed) {
  std::ostringstream s;
  s << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: " << n << " " << n + 3 << " " << n + 5
    << "\nencoding: raw\n\n";
  std::string bytes = s.str();
  uint32_t x = seed;
  for (uint32_t i = 0; i < n * (n + 3) * (n + 5); ++i)
    bytes.push_back(static_cast<char>((x = x * 1664525u + 1013904223u) >> 24));
  std::ofstream(path, std::ios::binary) << bytes;
}

TEST(MpiBatch, EveryFileOnceAndTheSameBytesAsOneProcess) {
  TempDir dir;
  std::ofstream list(dir.file("list.txt"));
  for (int i = 0; i < 12; ++i) {
    writeNrrd(dir.file(std::string("v") + std::to_string(i) + ".nrrd"), 8 + 6 * i,
              static_cast<uint8_t>(i));
    list << "v" << i << ".nrrd\n";
  }
  std::ofstream(dir.file("bad.nrrd")) << "not a volume";
  list << "bad.nrrd\n";
  list.close();
  const std::vector<std::string> common = {
      "convert", "--batch", dir.file("list.txt"), "--threshold", "200", "--threads", "1"};
  std::vector<std::string> many = common, one = common;
  many.insert(many.end(), {"--out-dir", dir.file("many")});
  one.insert(one.end(), {"--out-dir", dir.file("one")});
  const Launch split = runRanks(3, many);
  EXPECT_EQ(split.status, 1) << split.err;
  std::istringstream lines(split.out);
  std::set<std::string> inputs;
  nlohmann::json summary;
  for (std::string line; std::getline(lines, line);) {
    const auto j = nlohmann::json::parse(line);
    if (j.contains("summary")) {
      summary = j["summary"];
      continue;
    }
    EXPECT_TRUE(inputs.insert(j["input"].get<std::string>()).second) << "twice: " << j;
    EXPECT_EQ(j["status"], fs::path(j["input"].get<std::string>()).filename() == "bad.nrrd"
                               ? "failed"
                               : "converted")
        << j;
  }
  EXPECT_EQ(inputs.size(), 13u);
  EXPECT_EQ(summary["files"], 13);
  EXPECT_EQ(summary["converted"], 12);
  EXPECT_EQ(summary["failed"], 1);
  EXPECT_EQ(summary["ranks"], 3);
  const Launch single = runPlain(one);
  EXPECT_EQ(single.status, 1) << single.err;
  for (int i = 0; i < 12; ++i) {
    const std::string name = std::string("/v") + std::to_string(i) + ".vxl";
    EXPECT_EQ(readBytes(dir.file("one") + name), readBytes(dir.file("many") + name)) << name;
  }
}

}  // namespace
}  // namespace voxlink::testing
