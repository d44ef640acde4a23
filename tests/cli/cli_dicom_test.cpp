// SPDX-License-Identifier: BSD-3-Clause
// DICOM through the command line: `dicom list` (table and JSON) on a folder holding the CT head
// series and the RT Dose file, `convert --series`, and `info` reporting the dose scaling.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

namespace fs = std::filesystem;
constexpr const char* kSeries = "ct/slicer_CTHeadAxialDicom";
constexpr const char* kDose = "dicom_multiframe/pydicom_rtdose.dcm";
constexpr const char* kDoseUid = "1.2.777.777.77.7.7777.7777";

TEST(CliDicom, ListPickConvertAndReportTheDoseScaling) {
  VOXLINK_REQUIRE_DATA(kSeries);
  VOXLINK_REQUIRE_DATA(kDose);
  TempDir dir;
  const fs::path root = dir.path() / "export";
  fs::create_directories(root / "plan");
  fs::copy(dataPath(kSeries), root / "CT", fs::copy_options::recursive);
  fs::copy_file(dataPath(kDose), root / "plan" / "dose.dcm");

  auto r = runVoxlink({"dicom", "list", root.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("64x64x93"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("10x10x15"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(kDoseUid), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2 series"), std::string::npos) << r.out;

  r = runVoxlink({"dicom", "list", "--json", root.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["series"].size(), 2u);
  EXPECT_EQ(j["series"][0]["images"], 93);
  EXPECT_EQ(j["series"][1]["modality"], "RTDOSE");
  EXPECT_EQ(j["series"][1]["dims"], nlohmann::json::parse("[10, 10, 15]"));

  const std::string out = dir.file("dose.vxl");
  r = runVoxlink({"convert", root.string(), "--keep-all", "-o", out});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("holds 2 series; pick one with --series"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(out));

  r = runVoxlink({"convert", root.string(), "--series", kDoseUid, "--keep-all", "-o", out});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"info", out});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("rescaled by the reader (DoseGridScaling): source = file u32 * 1e-06 + 0"),
            std::string::npos)
      << r.out;
  r = runVoxlink({"info", "--json", out});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["reader_rescale"]["field"], "DoseGridScaling");

  // By index: the CT series is listed first (its files sort first).
  r = runVoxlink({"convert", root.string(), "--series", "1", "--threshold", "100", "-o", out});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"info", "--json", out});
  EXPECT_FALSE(nlohmann::json::parse(r.out).contains("reader_rescale"));

  r = runVoxlink({"dicom", "list", dir.file("nothing-here")});
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
}  // namespace voxlink::testing
