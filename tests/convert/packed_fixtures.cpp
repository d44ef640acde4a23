// SPDX-License-Identifier: BSD-3-Clause
#include "tests/convert/packed_fixtures.h"

#include <gtest/gtest.h>

#include <cstring>

#include "convert/converter.h"
#include "format/scalar_type.h"
#include "pack/open_file.h"
#include "pack/packed_file.h"
#include "sources/volume_source.h"

namespace voxlink::pack::test {

using format::FileHeader;
using format::sectionName;

std::string convertReal(const TempDir& dir, const std::string& relative, const char* threshold,
                        const char* valueType, uint32_t brickSize, Axis axis) {
  auto source = sources::openVolume(testing::dataPath(relative), {});
  EXPECT_TRUE(source) << source.message();
  convert::ConvertOptions options;
  options.brickSize = brickSize;
  options.axis = axis;
  options.classification = convert::thresholdClassification({threshold}).value();
  if (valueType) {
    options.storedType = parseStoredName(valueType);
    options.errorBound = 1e9;  // f16 rounds the larger values: allowed, the file stays valid
  }
  const std::string path = dir.file("in.vxl");
  auto converted = convert::convertVolume(**source, options, path);
  EXPECT_TRUE(converted) << converted.message();
  return path;
}

Packed packReal(const TempDir& dir, const std::string& path, bool predict) {
  Packed out;
  auto file = pack::openValidatedFile(path);
  EXPECT_TRUE(file) << file.message();
  PackOptions options;
  options.predictGradients = predict;
  auto report = packFile(*file, dir.file("packed.vxl"), options);
  EXPECT_TRUE(report) << report.message();
  out.original = testing::readBytes(path);
  out.packed = testing::readBytes(dir.file("packed.vxl"));
  return out;
}

std::vector<uint8_t> unpacked(const std::vector<uint8_t>& packed) {
  auto file = unpackFile(packed, "p.vxl", uint64_t{1} << 32);
  EXPECT_TRUE(file) << file.message();
  if (!file) return {};
  return {file->bytes().begin(), file->bytes().end()};
}

SectionEntry packedEntry(const std::vector<uint8_t>& packed, SectionId id) {
  FileHeader h;
  std::memcpy(&h, packed.data(), sizeof h);
  for (uint32_t i = 0; i < h.sectionCount; ++i) {
    SectionEntry e;
    std::memcpy(&e, packed.data() + h.sectionTableOffset + i * sizeof e, sizeof e);
    if (e.id == static_cast<uint32_t>(id)) return e;
  }
  ADD_FAILURE() << "no section " << sectionName(id);
  return {};
}

}  // namespace voxlink::pack::test
