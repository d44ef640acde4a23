// SPDX-License-Identifier: BSD-3-Clause
// The fuzz input's file bundle (fuzz/fuzz_input.h): how one input becomes several files.
#include "fuzz/fuzz_input.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace voxlink::fuzz {
namespace {

std::string text(std::span<const uint8_t> bytes) { return {bytes.begin(), bytes.end()}; }

std::vector<FuzzFile> split(const std::string& input, std::vector<uint8_t>& storage) {
  storage.assign(input.begin(), input.end());
  return splitFuzzFiles(storage, "main.nhdr");
}

TEST(SplitFuzzFiles, WholeInputIsTheMainFileWithoutMarkers) {
  std::vector<uint8_t> storage;
  const auto files = split("NRRD0004\nsizes: 1 1 1\n", storage);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].name, "main.nhdr");
  EXPECT_EQ(text(files[0].bytes), "NRRD0004\nsizes: 1 1 1\n");
}

TEST(SplitFuzzFiles, MarkerLinesStartNamedFiles) {
  std::vector<uint8_t> storage;
  const auto files = split("header\n==> a.raw <==\nAAAA\n==> b-1.raw <==\n", storage);
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(text(files[0].bytes), "header");
  EXPECT_EQ(files[1].name, "a.raw");
  EXPECT_EQ(text(files[1].bytes), "AAAA");
  EXPECT_EQ(files[2].name, "b-1.raw");
  EXPECT_EQ(text(files[2].bytes), "");
}

TEST(SplitFuzzFiles, NamesThatCouldLeaveTheFolderStayData) {
  std::vector<uint8_t> storage;
  for (const std::string bad : {"../x", "..", "a/b", "", "sp ace"}) {
    const std::string input = "h\n==> " + bad + " <==\nrest";
    const auto files = split(input, storage);
    ASSERT_EQ(files.size(), 1u) << bad;
    EXPECT_EQ(text(files[0].bytes), input);
  }
}

TEST(ScratchDir, WriteReplacesTheFilesOfTheLastRun) {
  ScratchDir dir;
  std::vector<uint8_t> storage;
  dir.write(split("one\n==> old.raw <==\nx", storage));
  const std::string main = dir.write(split("two", storage));
  EXPECT_TRUE(std::filesystem::exists(main));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "old.raw"));
}

}  // namespace
}  // namespace voxlink::fuzz
