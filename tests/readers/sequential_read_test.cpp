// SPDX-License-Identifier: BSD-3-Clause
// Every reader serves the same bytes whatever the slab size; rewind() starts over; compressed
// (sequential) sources refuse to go backwards without it.
#include <gtest/gtest.h>

#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

const char* const kInputs[] = {
    "ct/vtk_headsq/quarter.nhdr",                              // raw, one file per slice
    "ct/vtkjs_LIDC2/LIDC2.nhdr",                               // detached gzip
    "ct/openscivis_lossy/carp_128x128x256_uint16_lossy.nrrd",  // attached gzip, 16-bit
    "volume/vtk_frogtissue/frogtissue.mhd",                    // zlib .zraw
    "mri/niivue_mha.mha",                                      // LOCAL zlib
    "mri/vtk_avg152T1_RL_nifti.nii.gz",                        // gzip, big-endian header
    "ct/slicer_CTHeadAxialDicom",                              // one DICOM file per slice
    "ct/voreen_walnut/walnut.vvd",                             // mapped raw
    "volume/vtk_hydrogen.vti",                                 // decoded at open, in memory
};

class SequentialRead : public ::testing::TestWithParam<const char*> {};

TEST_P(SequentialRead, AnySlabSizeGivesTheSameBytes) {
  VOXLINK_REQUIRE_DATA(GetParam());
  auto source = openOrDie(dataPath(GetParam()));
  ASSERT_TRUE(source);
  auto whole = readAll(*source);
  ASSERT_TRUE(whole) << whole.message();
  for (uint32_t slab : {1u, 3u, 16u, 1000u}) {
    SCOPED_TRACE(slab);
    EXPECT_TRUE(readInSlabs(*source, slab) == *whole);
  }
}

TEST_P(SequentialRead, RewindAndSkippingAhead) {
  VOXLINK_REQUIRE_DATA(GetParam());
  auto source = openOrDie(dataPath(GetParam()));
  ASSERT_TRUE(source);
  const VolumeInfo& info = source->info();
  auto whole = readAll(*source);
  ASSERT_TRUE(whole) << whole.message();
  const uint32_t mid = info.dims[2] / 2;
  std::vector<uint8_t> slab(2 * info.sliceBytes());
  // Jump straight to the middle (a stream decodes and drops what lies before).
  ASSERT_TRUE(source->rewind().isOk());
  ASSERT_TRUE(source->read(mid, 2, slab.data()).isOk());
  EXPECT_TRUE(std::equal(slab.begin(), slab.end(),
                         whole->begin() + static_cast<long>(mid * info.sliceBytes())));
  // Going back: random-access sources allow it, streams ask for rewind().
  const Status back = source->read(1, 1, slab.data());
  if (source->randomAccess()) {
    EXPECT_TRUE(back.isOk());
  } else {
    expectError(back, ErrorCode::kInvalidArgument, {"rewind"});
    ASSERT_TRUE(source->rewind().isOk());
    ASSERT_TRUE(source->read(1, 1, slab.data()).isOk());
  }
  EXPECT_TRUE(std::equal(slab.begin(), slab.begin() + static_cast<long>(info.sliceBytes()),
                         whole->begin() + static_cast<long>(info.sliceBytes())));
  expectError(source->read(info.dims[2] - 1, 2, slab.data()), ErrorCode::kInvalidArgument,
              {"beyond z size"});
}

INSTANTIATE_TEST_SUITE_P(RealFiles, SequentialRead, ::testing::ValuesIn(kInputs),
                         [](const ::testing::TestParamInfo<const char*>& p) {
                           std::string name = std::filesystem::path(p.param).filename().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace voxlink::sources::testing
