// SPDX-License-Identifier: BSD-3-Clause
// MetaImage headers with LOCAL data or data files given as extra files (one, numbered, LIST).
#include "fuzz/targets/volume_readers.h"
#include "sources/readers/metaimage_reader.h"

namespace voxlink::fuzz {

Status fuzzMetaImage(Input input) {
  return openAndDrain(input, "input.mhd", sources::openMetaImage);
}

}  // namespace voxlink::fuzz
