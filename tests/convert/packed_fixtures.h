// SPDX-License-Identifier: BSD-3-Clause
// What the packed-file tests share: real CT converted, then packed and unpacked again.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "format/layout.h"
#include "tests/support/test_util.h"

namespace voxlink::pack::test {

using format::Axis;
using format::SectionEntry;
using format::SectionId;
using ::voxlink::testing::TempDir;

inline constexpr const char* kFoot = "ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd";
inline constexpr const char* kCarp = "ct/openscivis_lossy/carp_128x128x256_uint16_lossy.nrrd";

// Converts real data (a path under the data folder) into dir/in.vxl and returns that path.
std::string convertReal(const TempDir& dir, const std::string& relative, const char* threshold,
                        const char* valueType = nullptr, uint32_t brickSize = 8,
                        Axis axis = Axis::kZ);

struct Packed {
  std::vector<uint8_t> original, packed;
};

// Packs the file at `path` into dir/packed.vxl; both files' bytes.
Packed packReal(const TempDir& dir, const std::string& path, bool predict = true);

// The bytes `packed` unpacks to (none, after a failed expectation, if it does not).
std::vector<uint8_t> unpacked(const std::vector<uint8_t>& packed);

// The packed file's table entry of section `id`.
SectionEntry packedEntry(const std::vector<uint8_t>& packed, SectionId id);

}  // namespace voxlink::pack::test
