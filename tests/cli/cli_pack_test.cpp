// SPDX-License-Identifier: BSD-3-Clause
// voxlink pack / unpack as a user runs them: the unpacked file is the original byte for byte
// (a CT volume and a scene with surfaces and spheres), every command reads the packed file, and
// damage or misuse ends with one line, a non-zero exit and no output file.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "base/crc32c.h"
#include "format/layout.h"
#include "format/voxlink_file.h"
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

// A wiped section table was reported as "section PACK: missing", a non-zero reserved word of a
// PACK entry as an unknown codec, a reserved header byte as a checksum mismatch. Each now names
// its own cause.
TEST(CliPack, DamagedTableAndReservedWordsNameTheirCause) {
  TempDir dir;
  std::vector<uint8_t> ramp(8000);
  for (size_t i = 0; i < ramp.size(); ++i) ramp[i] = static_cast<uint8_t>(i % 251);
  writeBytes(dir.file("v.raw"), ramp);
  ASSERT_EQ(runVoxlink({"convert", dir.file("v.raw"), "--dims", "20,20,20", "--type", "u8",
                        "--keep-all", "-q", "-o", dir.file("v.vxl")})
                .status,
            0);
  ASSERT_EQ(runVoxlink({"pack", dir.file("v.vxl"), "-o", dir.file("p.vxl"), "-q"}).status, 0);
  const std::vector<uint8_t> packed = readBytes(dir.file("p.vxl"));
  format::FileHeader header;
  std::memcpy(&header, packed.data(), sizeof header);
  const uint64_t tableBytes = uint64_t{header.sectionCount} * sizeof(format::SectionEntry);
  ASSERT_LE(header.sectionTableOffset + tableBytes, packed.size());
  auto entryAt = [&](const std::vector<uint8_t>& bytes, size_t i) {
    format::SectionEntry e;
    std::memcpy(&e, bytes.data() + header.sectionTableOffset + i * sizeof e, sizeof e);
    return e;
  };
  auto unpackMessage = [&](const std::vector<uint8_t>& bytes, const std::string& name) {
    writeBytes(dir.file(name), bytes);
    auto r = runVoxlink({"unpack", dir.file(name), "-o", dir.file("u.vxl")});
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("u.vxl")));
    return r.err;
  };

  std::vector<uint8_t> wiped = packed;
  std::fill_n(wiped.begin() + std::ptrdiff_t(header.sectionTableOffset), tableBytes, 0);
  EXPECT_EQ(unpackMessage(wiped, "wiped.vxl"),
            "voxlink: " + dir.file("wiped.vxl") + ": section table entry 0 (at byte " +
                std::to_string(header.sectionTableOffset) +
                ") is all zeros: the section table is damaged\n");

  // The reserved word of the packed table's first entry.
  std::vector<uint8_t> reservedEntry = packed;
  const format::SectionEntry first = entryAt(packed, 0);
  const uint32_t five = 5;
  std::memcpy(reservedEntry.data() + header.sectionTableOffset + 28, &five, 4);
  const std::string firstName(format::sectionName(static_cast<format::SectionId>(first.id)));
  EXPECT_EQ(unpackMessage(reservedEntry, "reserved_entry.vxl"),
            "voxlink: " + dir.file("reserved_entry.vxl") + ": section " + firstName +
                ".reserved: 5 (must be 0)\n");

  // The reserved word of PACK's first entry, its checksum made right again.
  std::vector<uint8_t> reservedPack = packed;
  size_t packIndex = header.sectionCount;
  for (size_t i = 0; i < header.sectionCount; ++i)
    if (entryAt(packed, i).id == static_cast<uint32_t>(format::SectionId::kPack)) packIndex = i;
  ASSERT_LT(packIndex, header.sectionCount);
  format::SectionEntry pack = entryAt(packed, packIndex);
  const uint64_t firstPackEntry = pack.offset + 32;  // after the preamble
  format::SectionEntry original;
  std::memcpy(&original, packed.data() + firstPackEntry, sizeof original);
  std::memcpy(reservedPack.data() + firstPackEntry + 36, &five, 4);  // codec at 32, reserved 36
  pack.crc = base::crc32c(reservedPack.data() + pack.offset, pack.bytes);
  std::memcpy(reservedPack.data() + header.sectionTableOffset + packIndex * sizeof pack, &pack,
              sizeof pack);
  EXPECT_EQ(unpackMessage(reservedPack, "reserved_pack.vxl"),
            "voxlink: " + dir.file("reserved_pack.vxl") + ": section PACK: entry of " +
                std::string(format::sectionName(static_cast<format::SectionId>(original.id))) +
                ": reserved word 5 (must be 0)\n");

  // A reserved header byte, the packed header's checksum made right: it was reported as "the
  // restored header does not match" PACK's checksum of it.
  std::vector<uint8_t> reservedHeader = packed;
  format::FileHeader changed = header;
  changed.reserved[3] = 1;
  changed.headerCrc = format::headerChecksum(changed);
  std::memcpy(reservedHeader.data(), &changed, sizeof changed);
  EXPECT_EQ(
      unpackMessage(reservedHeader, "reserved_header.vxl"),
      "voxlink: " + dir.file("reserved_header.vxl") + ": header.reserved: byte 3 is not zero\n");
}

}  // namespace
}  // namespace voxlink::testing
