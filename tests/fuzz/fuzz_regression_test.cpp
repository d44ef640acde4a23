// SPDX-License-Identifier: BSD-3-Clause
// Kept fuzz findings replay as errors; real inputs through the same entry points are accepted
// (so "gives an error" is not what every input gets).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "fuzz/fuzz_targets.h"
#include "tests/support/test_util.h"

namespace voxlink::fuzz {
namespace {

namespace fs = std::filesystem;
using ::voxlink::testing::dataPath;
using ::voxlink::testing::readBytes;

const fs::path kRegressions = VOXLINK_FUZZ_REGRESSION_DIR;

std::vector<std::string> targetNames() {
  std::vector<std::string> names;
  for (const FuzzTarget& t : fuzzTargets()) names.emplace_back(t.name);
  return names;
}

class FuzzRegression : public ::testing::TestWithParam<std::string> {};

TEST_P(FuzzRegression, KeptInputsGiveErrors) {
  const fs::path dir = kRegressions / GetParam();
  if (!fs::is_directory(dir)) GTEST_SKIP() << "no kept inputs for " << GetParam();
  const FuzzTarget* target = findFuzzTarget(GetParam());
  ASSERT_NE(target, nullptr);
  std::vector<fs::path> inputs;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().filename() != "README.md")
      inputs.push_back(entry.path());
  std::sort(inputs.begin(), inputs.end());
  ASSERT_FALSE(inputs.empty()) << dir << " holds no inputs";
  for (const fs::path& input : inputs) {
    const std::vector<uint8_t> bytes = readBytes(input.string());
    const Status status = target->run(bytes);
    EXPECT_FALSE(status.isOk()) << input << " was accepted";
    if (!status.isOk()) {
      // One line, as every library message.
      EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzRegression, ::testing::ValuesIn(targetNames()),
                         [](const auto& param) { return param.param; });

TEST(FuzzRegressionFolders, EveryFolderNamesATarget) {
  if (!fs::is_directory(kRegressions)) GTEST_SKIP() << "no kept inputs";
  for (const auto& entry : fs::directory_iterator(kRegressions)) {
    if (!entry.is_directory()) continue;
    EXPECT_NE(findFuzzTarget(entry.path().filename().string()), nullptr)
        << entry.path() << " is not the name of a fuzz target";
  }
}

std::vector<uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

void append(std::vector<uint8_t>& to, const std::vector<uint8_t>& more) {
  to.insert(to.end(), more.begin(), more.end());
}

TEST(FuzzEntryPoints, AcceptNumberedNrrdFromRealSlices) {
  VOXLINK_REQUIRE_DATA("ct/vtk_headsq/quarter.nhdr");
  std::vector<uint8_t> input = bytesOf(
      "NRRD0004\ndimension: 3\nsizes: 64 64 2\nendian: little\ntype: short\n"
      "encoding: raw\ndata file: quarter.%d 1 2 1\n");
  for (int i = 1; i <= 2; ++i) {
    append(input, bytesOf("\n==> quarter." + std::to_string(i) + " <==\n"));
    append(input, readBytes(dataPath("ct/vtk_headsq/quarter." + std::to_string(i))));
  }
  const Status status = findFuzzTarget("nrrd")->run(input);
  EXPECT_TRUE(status.isOk()) << status.message();
}

TEST(FuzzEntryPoints, AcceptRealSamplesAndTransferFunction) {
  VOXLINK_REQUIRE_DATA("geostat/gstat_csv/walker.csv");
  Status status =
      findFuzzTarget("kriging_points")->run(readBytes(dataPath("geostat/gstat_csv/walker.csv")));
  EXPECT_TRUE(status.isOk()) << status.message();
  status =
      findFuzzTarget("transfer_function")
          ->run(readBytes(std::string(VOXLINK_SOURCE_DIR) + "/samples/headsq/skin-bone.tf.json"));
  EXPECT_TRUE(status.isOk()) << status.message();
}

TEST(FuzzEntryPoints, RawTakesItsOptionsFromTheFirstBytes) {
  // 2 x 3 x 1 voxels, type byte 0 (u8), little endian, no header bytes, then 6 voxels.
  std::vector<uint8_t> input{2, 0, 3, 0, 1, 0, 0, 0, 1, 2, 3, 4, 5, 6};
  EXPECT_TRUE(findFuzzTarget("raw")->run(input).isOk());
  input.pop_back();  // one voxel short
  EXPECT_FALSE(findFuzzTarget("raw")->run(input).isOk());
}

}  // namespace
}  // namespace voxlink::fuzz
