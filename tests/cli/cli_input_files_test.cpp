// SPDX-License-Identifier: BSD-3-Clause
// -o may not name any file an input reads, not only the path on the command line: a detached
// NRRD's or MetaImage's data files (one or a list), a DICOM folder's slices, the data file of a
// scene's volume object, an image of a stack, a VVD's raw file, the source `render --reference`
// reads. Each was overwritten with exit status 0 before.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/cli/run_command.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

namespace fs = std::filesystem;

void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// `bytes` bytes of a ramp, so a replaced file is told from the original.
std::vector<uint8_t> ramp(size_t bytes) {
  std::vector<uint8_t> v(bytes);
  for (size_t i = 0; i < bytes; ++i) v[i] = static_cast<uint8_t>(i % 251);
  return v;
}

void expectRefused(const CommandResult& r, const std::string& out, const std::string& file,
                   const std::string& input) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err, "voxlink: " + out + ": output is " + file + ", a file the input " + input +
                       " reads; give another output name\n");
}

CommandResult convertTo(const std::string& input, const std::string& out) {
  return runVoxlink({"convert", input, "--keep-all", "-q", "-o", out});
}

TEST(CliInputFiles, ConvertSparesTheNrrdDataFiles) {
  TempDir dir;
  const std::vector<uint8_t> data = ramp(8000);
  writeBytes(dir.file("neghip.raw"), data);
  writeText(dir.file("n.nhdr"),
            "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 20 20 20\nencoding: raw\n"
            "data file: neghip.raw\n\n");
  expectRefused(convertTo(dir.file("n.nhdr"), dir.file("neghip.raw")), dir.file("neghip.raw"),
                dir.file("neghip.raw"), dir.file("n.nhdr"));
  EXPECT_EQ(readBytes(dir.file("neghip.raw")), data);
  // A numbered list of slabs: every file of it.
  const std::vector<uint8_t> half(data.begin(), data.begin() + 4000);
  writeBytes(dir.file("part1.raw"), half);
  writeBytes(dir.file("part2.raw"), half);
  writeText(dir.file("list.nhdr"),
            "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 20 20 20\nencoding: raw\n"
            "data file: part%d.raw 1 2 1\n\n");
  expectRefused(convertTo(dir.file("list.nhdr"), dir.file("part2.raw")), dir.file("part2.raw"),
                dir.file("part2.raw"), dir.file("list.nhdr"));
  EXPECT_EQ(readBytes(dir.file("part2.raw")), half);
  // Another name is written as before.
  EXPECT_EQ(convertTo(dir.file("list.nhdr"), dir.file("ok.vxl")).status, 0);
}

TEST(CliInputFiles, ConvertSparesMetaImageElementDataFiles) {
  TempDir dir;
  const std::vector<uint8_t> data = ramp(8000);
  writeBytes(dir.file("v.raw"), data);
  const std::string head =
      "ObjectType = Image\nNDims = 3\nDimSize = 20 20 20\nElementType = "
      "MET_UCHAR\n";
  writeText(dir.file("v.mhd"), head + "ElementDataFile = v.raw\n");
  expectRefused(convertTo(dir.file("v.mhd"), dir.file("v.raw")), dir.file("v.raw"),
                dir.file("v.raw"), dir.file("v.mhd"));
  const std::vector<uint8_t> slab(data.begin(), data.begin() + 4000);
  writeBytes(dir.file("a.raw"), slab);
  writeBytes(dir.file("b.raw"), slab);
  writeText(dir.file("l.mhd"), head + "ElementDataFile = LIST 3D\na.raw\nb.raw\n");
  expectRefused(convertTo(dir.file("l.mhd"), dir.file("b.raw")), dir.file("b.raw"),
                dir.file("b.raw"), dir.file("l.mhd"));
  EXPECT_EQ(readBytes(dir.file("v.raw")), data);
  EXPECT_EQ(readBytes(dir.file("b.raw")), slab);
}

TEST(CliInputFiles, ConvertSparesTheSlicesOfADicomFolder) {
  const std::string kSeries = "ct/slicer_CTHeadAxialDicom";
  VOXLINK_REQUIRE_DATA(kSeries);
  TempDir dir;
  const std::string folder = dir.file("dcm");
  fs::create_directories(folder);
  for (const auto& entry : fs::directory_iterator(dataPath(kSeries)))
    fs::copy_file(entry.path(), fs::path(folder) / entry.path().filename());
  const std::string slice = folder + "/CTHead3.dcm";
  const std::vector<uint8_t> before = readBytes(slice);
  expectRefused(convertTo(folder, slice), slice, slice, folder);
  EXPECT_EQ(readBytes(slice), before);
}

// A folder of 8x8 PGM slices, each a ramp offset by its slice number.
std::vector<std::string> writePgmStack(const std::string& folder, int slices) {
  fs::create_directories(folder);
  std::vector<std::string> files;
  for (int z = 0; z < slices; ++z) {
    std::vector<uint8_t> bytes = {'P', '5', '\n', '8', ' ', '8', '\n', '2', '5', '5', '\n'};
    for (int i = 0; i < 64; ++i) bytes.push_back(static_cast<uint8_t>(i + z));
    files.push_back(folder + "/s" + std::to_string(z + 1) + ".pgm");
    writeBytes(files.back(), bytes);
  }
  return files;
}

TEST(CliInputFiles, ConvertSparesTheImagesOfAStack) {
  TempDir dir;
  const std::string folder = dir.file("stack");
  const std::vector<std::string> slices = writePgmStack(folder, 4);
  const std::vector<uint8_t> before = readBytes(slices[1]);
  expectRefused(convertTo(folder, slices[1]), slices[1], slices[1], folder);
  EXPECT_EQ(readBytes(slices[1]), before);
  EXPECT_EQ(convertTo(folder, dir.file("ok.vxl")).status, 0);
}

TEST(CliInputFiles, ConvertSparesTheRawFileOfAVvd) {
  TempDir dir;
  const std::vector<uint8_t> data = ramp(8000);
  writeBytes(dir.file("v.raw"), data);
  writeText(dir.file("v.vvd"), R"(<?xml version="1.0" ?><VoreenData version="1"><Volumes><Volume>)"
                               R"(<RawData filename="v.raw" format="uint8" x="20" y="20" z="20" />)"
                               R"(</Volume></Volumes></VoreenData>)");
  expectRefused(convertTo(dir.file("v.vvd"), dir.file("v.raw")), dir.file("v.raw"),
                dir.file("v.raw"), dir.file("v.vvd"));
  EXPECT_EQ(readBytes(dir.file("v.raw")), data);
  EXPECT_EQ(convertTo(dir.file("v.vvd"), dir.file("ok.vxl")).status, 0);
}

// render writes its image before the reference reads the dense source: an image of a PNG stack
// was replaced by the render of the volume made from that stack.
TEST(CliInputFiles, RenderReferenceSparesTheImagesOfItsSource) {
  if (runVoxlink({"render", "--help"}).status != 0) GTEST_SKIP() << "built without the viewer";
  TempDir dir;
  writeBytes(dir.file("v.raw"), ramp(8000));
  ASSERT_EQ(runVoxlink({"convert", dir.file("v.raw"), "--dims", "20,20,20", "--type", "u8",
                        "--keep-all", "-q", "-o", dir.file("v.vxl")})
                .status,
            0);
  // The stack's slices are renders (RGBA PNGs; a stack reads channel 0).
  const std::string folder = dir.file("stack");
  fs::create_directories(folder);
  for (const char* name : {"s1.png", "s2.png", "s3.png"}) {
    auto r = runVoxlink({"render", dir.file("v.vxl"), "-o", folder + "/" + name, "--size", "8x8"});
    if (r.status != 0) GTEST_SKIP() << "no headless GL here: " << r.err;
  }
  ASSERT_EQ(convertTo(folder, dir.file("st.vxl")).status, 0);
  const std::string slice = folder + "/s2.png";
  const std::vector<uint8_t> before = readBytes(slice);
  for (const std::vector<std::string>& target :
       {std::vector<std::string>{"-o", slice},
        {"-o", dir.file("ok.png"), "--reference-output", slice}}) {
    std::vector<std::string> args = {"render", dir.file("st.vxl"), "--reference", "--source",
                                     folder,   "--size",           "8x8"};
    args.insert(args.end(), target.begin(), target.end());
    expectRefused(runVoxlink(args), slice, slice, folder);
    EXPECT_EQ(readBytes(slice), before);
  }
  EXPECT_FALSE(fs::exists(dir.file("ok.png")));
}

TEST(CliInputFiles, SceneBuildSparesTheDataFileOfItsVolume) {
  TempDir dir;
  const std::vector<uint8_t> data = ramp(8000);
  writeBytes(dir.file("v.raw"), data);
  writeText(dir.file("v.nhdr"),
            "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 20 20 20\nencoding: raw\n"
            "data file: v.raw\n\n");
  writeText(dir.file("s.scene.json"),
            R"({"objects": [{"type": "volume", "file": "v.nhdr", "threshold": 100}]})");
  auto r = runVoxlink({"scene", "build", dir.file("s.scene.json"), "-o", dir.file("v.raw")});
  expectRefused(r, dir.file("v.raw"), dir.file("v.raw"), dir.file("s.scene.json"));
  EXPECT_EQ(readBytes(dir.file("v.raw")), data);
  EXPECT_EQ(
      runVoxlink({"scene", "build", dir.file("s.scene.json"), "-o", dir.file("s.vxl")}).status, 0);
}

TEST(CliInputFiles, SceneBuildSparesAnObjsMaterialLibrary) {
  TempDir dir;
  writeText(dir.file("m.obj"), "mtllib look.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
  const std::string mtl = "newmtl red\nKd 1 0 0\n";
  writeText(dir.file("look.mtl"), mtl);
  writeText(dir.file("s.scene.json"), R"({"objects": [{"type": "mesh", "file": "m.obj"}]})");
  auto r = runVoxlink({"scene", "build", dir.file("s.scene.json"), "-o", dir.file("look.mtl")});
  expectRefused(r, dir.file("look.mtl"), dir.file("look.mtl"), dir.file("s.scene.json"));
  std::ifstream in(dir.file("look.mtl"));
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), mtl);
}

}  // namespace
}  // namespace voxlink::testing
