// SPDX-License-Identifier: BSD-3-Clause
// openVolume() picks the reader by name ending, folder content or magic bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "sources/readers/detail/reader_registry.h"
#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

TEST(ReaderRegistry, EveryReaderIsRegistered) {
  const auto names = readerNames();
  for (const char* name :
       {"nrrd", "metaimage", "nifti", "vvd", "vdb", "vti", "dicom", "image-stack", "raw"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

TEST(ReaderRegistry, PathsGoToTheirReaders) {
  VOXLINK_REQUIRE_DATA("ct/vtk_headsq/quarter.nhdr");
  const std::pair<const char*, const char*> cases[] = {
      {"ct/vtk_headsq/quarter.nhdr", "nrrd"},
      {"mri/niivue_FLAIR.nrrd", "nrrd"},
      {"volume/vtk_frogtissue/frogtissue.mhd", "metaimage"},
      {"mri/niivue_mha.mha", "metaimage"},
      {"mri/vtk_avg152T1_RL_nifti.nii.gz", "nifti"},
      {"ct/voreen_walnut/walnut.vvd", "vvd"},
      {"ct/slicer_CTHeadAxialDicom", "dicom"},
      {"volume/vtk_hydrogen.vti", "vti"},
  };
  for (const auto& [path, format] : cases) {
    SCOPED_TRACE(path);
    auto source = openOrDie(dataPath(path));
    ASSERT_TRUE(source);
    EXPECT_EQ(source->info().format, format);
  }
}

TEST(ReaderRegistry, MagicFormatOptionAndFallbacks) {
  VOXLINK_REQUIRE_DATA("volume/voreen_nucleon/nucleon.nrrd");
  TempDir dir;
  // A NRRD without its extension is found by its first bytes.
  writeWithHeader(dir.file("volume.dat"),
                  "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n",
                  patternBytes(8));
  auto magic = openOrDie(dir.file("volume.dat"));
  ASSERT_TRUE(magic);
  EXPECT_EQ(magic->info().format, "nrrd");
  // --format raw reads the nucleon data file as headerless raw.
  OpenOptions raw;
  raw.format = "raw";
  raw.dims = std::array<uint32_t, 3>{41, 41, 41};
  raw.type = ScalarType::kU8;
  auto forced = openOrDie(dataPath("volume/voreen_nucleon/nucleon.raw"), raw);
  ASSERT_TRUE(forced);
  EXPECT_EQ(forced->info().format, "raw");
  OpenOptions unknown;
  unknown.format = "bmp3d";
  expectError(openVolume(dir.file("volume.dat"), unknown), ErrorCode::kInvalidArgument,
              {"bmp3d", "nrrd", "dicom"});
  writeBytes(dir.file("mystery.xyz"), patternBytes(8));
  expectError(openVolume(dir.file("mystery.xyz")), ErrorCode::kUnsupported,
              {"mystery.xyz", "unknown volume format"});
  // A folder without DICOM files is an image stack (here an empty one).
  std::filesystem::create_directory(dir.file("empty"));
  expectError(openVolume(dir.file("empty")), ErrorCode::kCorrupt, {"empty", "no slice images"});
}

TEST(ReaderRegistry, VariableIsRefusedByFormatsWithoutNamedVariables) {
  TempDir dir;
  writeWithHeader(dir.file("volume.nrrd"),
                  "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n",
                  patternBytes(8));
  writeBytes(dir.file("volume.bin"), patternBytes(8));
  OpenOptions options;
  options.variable = "density";
  // It was ignored: the only variable was read as if it were 'density'.
  expectError(openVolume(dir.file("volume.nrrd"), options), ErrorCode::kInvalidArgument,
              {"volume.nrrd", "--variable 'density'", "nrrd reader has no named variables"});
  options.dims = std::array<uint32_t, 3>{2, 2, 2};
  options.type = ScalarType::kU8;
  expectError(openVolume(dir.file("volume.bin"), options), ErrorCode::kInvalidArgument,
              {"volume.bin", "raw reader"});
  options.format = "raw";
  expectError(openVolume(dir.file("volume.nrrd"), options), ErrorCode::kInvalidArgument,
              {"volume.nrrd", "raw reader"});
  options.variable.clear();
  EXPECT_TRUE(openOrDie(dir.file("volume.bin"), options));
}

TEST(ReaderRegistry, LowerExtensionKeepsGz) {
  EXPECT_EQ(lowerExtension("/a/B.NII.GZ"), ".nii.gz");
  EXPECT_EQ(lowerExtension("x.nrrd"), ".nrrd");
  EXPECT_EQ(lowerExtension("quarter"), "");
}

}  // namespace
}  // namespace voxlink::sources::testing
