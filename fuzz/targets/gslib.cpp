// SPDX-License-Identifier: BSD-3-Clause
// GSLIB / GEO-EAS grids: plain text, or (zip magic "PK") the single member of a .zip.
#include "fuzz/targets/volume_readers.h"
#include "sources/readers/gslib_reader.h"

namespace voxlink::fuzz {

Status fuzzGslib(Input input) {
  return openAndDrain(input, startsWithZip(input) ? "input.gslib.zip" : "input.gslib",
                      sources::openGslib);
}

}  // namespace voxlink::fuzz
