// SPDX-License-Identifier: BSD-3-Clause
// Image stacks through the OpenImageIO plugin: one file (a multi-page TIFF when it starts with
// a TIFF byte-order mark, else PNG), or a folder when the input carries extra slice files.
#include "fuzz/targets/volume_readers.h"
#include "sources/readers/image_stack_reader.h"

namespace voxlink::fuzz {

Status fuzzImageStack(Input input) {
  const bool tiff = input.size() >= 2 &&
                    ((input[0] == 'I' && input[1] == 'I') || (input[0] == 'M' && input[1] == 'M'));
  const auto files = splitFuzzFiles(input, tiff ? "slice0.tif" : "slice0.png");
  return openAndDrain(input, files.front().name, sources::openImageStack, {}, files.size() > 1);
}

}  // namespace voxlink::fuzz
