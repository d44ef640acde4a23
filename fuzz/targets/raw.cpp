// SPDX-License-Identifier: BSD-3-Clause
// Headerless raw volumes. The first 8 bytes stand for the command line (--dims as three
// little-endian u16, --type, then byte order and --header-bytes); the rest is the file.
#include "fuzz/targets/volume_readers.h"
#include "sources/readers/raw_reader.h"

namespace voxlink::fuzz {

Status fuzzRaw(Input input) {
  constexpr size_t kOptionBytes = 8;
  if (input.size() < kOptionBytes) return makeError(ErrorCode::kTruncated, "fuzz: no options");
  sources::OpenOptions options;
  std::array<uint32_t, 3> dims{};
  for (int a = 0; a < 3; ++a) dims[a] = input[2 * a] | (uint32_t{input[2 * a + 1]} << 8);
  options.dims = dims;
  options.type = static_cast<ScalarType>(input[6] % 8 + 1);
  options.endian = (input[7] & 0x80) ? sources::Endian::kBig : sources::Endian::kLittle;
  options.headerBytes = input[7] & 0x7f;
  return openAndDrain(input.subspan(kOptionBytes), "input.raw", sources::openRaw, options);
}

}  // namespace voxlink::fuzz
