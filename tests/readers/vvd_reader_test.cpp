// SPDX-License-Identifier: BSD-3-Clause
// Voreen .vvd: the walnut header's RawData and meta items, values = the raw file's bytes.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

TEST(VvdReader, WalnutMatchesItsRawFile) {
  VOXLINK_REQUIRE_DATA("ct/voreen_walnut/walnut.vvd");
  auto source = openOrDie(dataPath("ct/voreen_walnut/walnut.vvd"));
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  EXPECT_EQ(info.format, "vvd");
  EXPECT_EQ(info.dims, (std::array<uint32_t, 3>{128, 96, 114}));
  EXPECT_EQ(info.type, ScalarType::kU16);
  EXPECT_EQ(info.spacing, (std::array<double, 3>{0.015625, 0.015625, 0.015625}));
  EXPECT_EQ(info.origin, (std::array<double, 3>{-1, -0.75, -0.890625}));
  auto data = readAll(*source);
  ASSERT_TRUE(data) << data.message();
  const auto raw = readBytes(dataPath("ct/voreen_walnut/walnut.raw"));
  EXPECT_TRUE(*data == raw);
  // README: exact values 0..22526.
  uint16_t top = 0;
  for (size_t i = 0; i < raw.size(); i += 2)
    top = std::max<uint16_t>(top, uint16_t(raw[i] | raw[i + 1] << 8));
  EXPECT_EQ(top, 22526);
}

// A header cut inside an attribute (the walnut's long preview) is a cut header, as one cut
// between elements; XML broken before the cut is named as such.
TEST(VvdReader, HeaderCutInsideAnAttributeIsTruncated) {
  VOXLINK_REQUIRE_DATA("ct/voreen_walnut/walnut.vvd");
  TempDir dir;
  const auto header = readBytes(dataPath("ct/voreen_walnut/walnut.vvd"));
  const std::string text(header.begin(), header.end());
  const size_t preview = text.find("prevData=\"");
  ASSERT_NE(preview, std::string::npos);
  writeText(dir.file("cut.vvd"), text.substr(0, preview + 40));
  expectError(openVolume(dir.file("cut.vvd")), ErrorCode::kTruncated,
              {"cut.vvd", "<Volume>", "not closed"});
  std::string broken = text;
  broken.replace(preview, 10, "prevData ");
  writeText(dir.file("broken.vvd"), broken);
  expectError(openVolume(dir.file("broken.vvd")), ErrorCode::kCorrupt,
              {"broken.vvd", "XML at byte", "<DerivedItem>"});
}

TEST(VvdReader, BadHeadersNameTheField) {
  TempDir dir;
  const std::string body =
      R"(<?xml version="1.0" ?><VoreenData version="1"><Volumes><Volume>)"
      R"(<RawData filename="v.raw" format="FORMAT" x="4" y="3" z="2" /></Volume></Volumes></VoreenData>)";
  auto header = [&](const std::string& format) {
    std::string s = body;
    s.replace(s.find("FORMAT"), 6, format);
    return s;
  };
  writeBytes(dir.file("v.raw"), patternBytes(4 * 3 * 2 * 2));
  writeText(dir.file("ok.vvd"), header("int16"));
  auto ok = openOrDie(dir.file("ok.vvd"));
  ASSERT_TRUE(ok);
  EXPECT_TRUE(hasNote(ok->info(), "no Spacing")) << notesOf(ok->info());
  writeText(dir.file("vec.vvd"), header("Vector3(uint8)"));
  expectError(openVolume(dir.file("vec.vvd")), ErrorCode::kUnsupported,
              {"vec.vvd", "format", "Vector3(uint8)"});
  writeText(dir.file("big.vvd"), header("uint32"));  // 96 bytes needed, 48 present
  expectError(openVolume(dir.file("big.vvd")), ErrorCode::kTruncated,
              {"big.vvd", "RawData filename", "v.raw"});
  const std::string cut = header("int16").substr(0, header("int16").find("</Volume>"));
  writeText(dir.file("cut.vvd"), cut);
  expectError(openVolume(dir.file("cut.vvd")), ErrorCode::kTruncated,
              {"cut.vvd", "<Volume>", "not closed"});
  std::filesystem::remove(dir.file("v.raw"));
  expectError(openVolume(dir.file("ok.vvd")), ErrorCode::kIo,
              {"ok.vvd", "RawData filename", "v.raw does not exist"});
}

}  // namespace
}  // namespace voxlink::sources::testing
