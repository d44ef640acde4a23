// SPDX-License-Identifier: BSD-3-Clause
// Voreen .vvd XML headers; the raw file they name is an extra file.
#include "fuzz/targets/volume_readers.h"
#include "sources/readers/vvd_reader.h"

namespace voxlink::fuzz {

Status fuzzVvd(Input input) { return openAndDrain(input, "input.vvd", sources::openVvd); }

}  // namespace voxlink::fuzz
