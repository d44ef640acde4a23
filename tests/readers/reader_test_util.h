// SPDX-License-Identifier: BSD-3-Clause
// Helpers for the reader tests: opening with a readable failure, reading a whole volume in
// slabs of any size, and independent decoders (zlib's own gz API) for expected bytes.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sources/volume_source.h"
#include "tests/support/test_util.h"

namespace voxlink::sources::testing {

using ::voxlink::testing::dataPath;
using ::voxlink::testing::readBytes;
using ::voxlink::testing::TempDir;
using ::voxlink::testing::writeBytes;

// openVolume() that fails the test (with the message) instead of returning an error.
std::unique_ptr<VolumeSource> openOrDie(const std::string& path, const OpenOptions& options = {});

// Reads slices [0, dims.z) in slabs of `slab` slices, after rewind().
std::vector<uint8_t> readInSlabs(VolumeSource& source, uint32_t slab);

// Decodes a whole gzip or zlib byte string with zlib's one-shot/gz APIs (not our stream).
std::vector<uint8_t> gunzipFile(const std::string& path);
std::vector<uint8_t> inflateBytes(const uint8_t* data, size_t size, size_t expectedSize);

// gzip (zlib's deflate with a gzip wrapper) or zlib framing of `data`.
std::vector<uint8_t> gzipBytes(const std::vector<uint8_t>& data, bool gzipWrapper = true);
void writeText(const std::string& path, const std::string& text);
// A header followed by binary data in one file.
void writeWithHeader(const std::string& path, const std::string& header,
                     const std::vector<uint8_t>& data);
// Deterministic test volume bytes (a value pattern that differs per voxel and slice).
std::vector<uint8_t> patternBytes(size_t n, uint32_t seed = 1);

// The bytes of `path` after the first "\n\n" (an attached NRRD header).
std::vector<uint8_t> bytesAfterBlankLine(const std::string& path);

// Reverses the order of z slices of `sliceBytes` each.
std::vector<uint8_t> flipZ(const std::vector<uint8_t>& data, uint64_t sliceBytes);

// Swaps each `elementBytes` group (big-endian test data).
std::vector<uint8_t> swapped(std::vector<uint8_t> data, size_t elementBytes);

bool hasNote(const VolumeInfo& info, const std::string& fragment);
std::string notesOf(const VolumeInfo& info);

// Asserts code and that the message contains every fragment.
void expectError(const Status& status, ErrorCode code,
                 std::initializer_list<std::string> fragments);
template <class T>
void expectError(const Result<T>& result, ErrorCode code,
                 std::initializer_list<std::string> fragments) {
  expectError(result.status(), code, fragments);
}

// Opens then reads everything, returning the first error (open or read).
Status openAndReadAll(const std::string& path, const OpenOptions& options = {});

}  // namespace voxlink::sources::testing
