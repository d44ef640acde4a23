// voxlink pack / unpack as a user runs them: the unpacked file is the original byte for byte
// (a CT volume and a scene with surfaces and spheres), every command reads the packed file, and
// damage or misuse ends with one line, a non-zero exit and no output file.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

constexpr const char* kFoot = "ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd";

bool oneLine(const std::string& err) { return !err.empty() && err.find('\n') == err.size() - 1; }

TEST(CliPack, VolumeRoundTripsAndEveryCommandReadsThePackedFile) {
  VOXLINK_REQUIRE_DATA(kFoot);
  TempDir dir;
  const std::string vxl = dir.file("foot.vxl"), packed = dir.file("foot.packed.vxl"),
                    back = dir.file("foot.back.vxl");
  auto r = runVoxlink({"convert", dataPath(kFoot), "--threshold", "60", "-o", vxl, "-q"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"pack", vxl, "-o", packed, "--sections"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("predicted-f32+zstd"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("B/voxel"), std::string::npos) << r.out;
  EXPECT_LT(std::filesystem::file_size(packed), std::filesystem::file_size(vxl) * 6 / 10);
  r = runVoxlink({"unpack", packed, "-o", back});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(readBytes(back), readBytes(vxl));

  r = runVoxlink({"validate", packed});
  EXPECT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"info", packed, "--no-vdb"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("packed on disk"), std::string::npos) << r.out;
  r = runVoxlink({"info", packed, "--no-vdb", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"packed_bytes\": " + std::to_string(std::filesystem::file_size(packed))),
            std::string::npos)
      << r.out;
  r = runVoxlink({"export", packed, "-o", dir.file("a.nrrd")});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"export", vxl, "-o", dir.file("b.nrrd")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(readBytes(dir.file("a.nrrd")), readBytes(dir.file("b.nrrd")));
}

TEST(CliPack, SceneWithSurfacesAndSpheresRoundTrips) {
  VOXLINK_REQUIRE_DATA(kFoot);
  VOXLINK_REQUIRE_DATA("mesh/c3dtm_stanford-bunny.obj");
  TempDir dir;
  const std::string scene = std::string(VOXLINK_SAMPLE_SCENES) + "/foot-bunny.scene.json";
  auto r = runVoxlink({"scene", "build", scene, "-o", dir.file("s.vxl")});
  ASSERT_EQ(r.status, 0) << r.err;
  r = runVoxlink({"pack", dir.file("s.vxl"), "-o", dir.file("p.vxl"), "-q"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  r = runVoxlink({"unpack", dir.file("p.vxl"), "-o", dir.file("u.vxl"), "-q"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(readBytes(dir.file("u.vxl")), readBytes(dir.file("s.vxl")));

  // The scene's volume samples (VMSK slots) are predicted as the foot's voxels are in a volume
  // file of their own: surface and sphere voxels count as removed neighbours, as the converter
  // saw them, so GRAD packs to exactly the same bytes.
  auto gradLine = [](const std::string& table) {
    const size_t at = table.find("\nGRAD");
    return at == std::string::npos ? std::string()
                                   : table.substr(at + 1, table.find('\n', at + 1) - at - 1);
  };
  r = runVoxlink({"pack", dir.file("s.vxl"), "-o", dir.file("p2.vxl"), "--sections"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string sceneGrad = gradLine(r.out);
  EXPECT_NE(sceneGrad.find("predicted-f32+zstd"), std::string::npos) << r.out;
  ASSERT_EQ(
      runVoxlink({"convert", dataPath(kFoot), "--threshold", "60", "-o", dir.file("f.vxl"), "-q"})
          .status,
      0);
  r = runVoxlink({"pack", dir.file("f.vxl"), "-o", dir.file("fp.vxl"), "--sections"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(sceneGrad, gradLine(r.out));
}

TEST(CliPack, MisuseAndDamageEndWithOneLineAndNoOutput) {
  VOXLINK_REQUIRE_DATA(kFoot);
  TempDir dir;
  const std::string vxl = dir.file("foot.vxl"), packed = dir.file("p.vxl");
  ASSERT_EQ(runVoxlink({"convert", dataPath(kFoot), "--threshold", "60", "-o", vxl, "-q"}).status,
            0);
  ASSERT_EQ(runVoxlink({"pack", vxl, "-o", packed, "-q"}).status, 0);

  auto r = runVoxlink({"pack", vxl, "-o", vxl});  // the input itself
  EXPECT_NE(r.status, 0);
  EXPECT_TRUE(oneLine(r.err)) << r.err;
  r = runVoxlink({"pack", packed, "-o", dir.file("twice.vxl")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("already packed"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("twice.vxl")));
  r = runVoxlink({"unpack", vxl, "-o", dir.file("u.vxl")});
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("not a packed file"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("u.vxl")));

  // A flipped byte in the middle of the packed file: every reader refuses it the same way.
  std::vector<uint8_t> bytes = readBytes(packed);
  bytes[bytes.size() / 2] ^= 0x10;
  writeBytes(dir.file("bad.vxl"), bytes);
  for (const char* command : {"validate", "info", "unpack"}) {
    std::vector<std::string> args = {command, dir.file("bad.vxl")};
    if (std::string(command) == "unpack") args.insert(args.end(), {"-o", dir.file("u.vxl")});
    if (std::string(command) == "info") args.push_back("--no-vdb");
    r = runVoxlink(args);
    EXPECT_NE(r.status, 0) << command;
    EXPECT_TRUE(oneLine(r.err)) << command << ": " << r.err;
    EXPECT_NE(r.err.find("checksum mismatch"), std::string::npos) << command << ": " << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("u.vxl")));
}

}  // namespace
}  // namespace voxlink::testing
