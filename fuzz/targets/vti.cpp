// SPDX-License-Identifier: BSD-3-Clause
// VTK XML image data: inline or appended data, base64 or raw, zlib blocks.
#include "fuzz/targets/volume_readers.h"
#include "sources/readers/vti_reader.h"

namespace voxlink::fuzz {

Status fuzzVti(Input input) { return openAndDrain(input, "input.vti", sources::openVti); }

}  // namespace voxlink::fuzz
