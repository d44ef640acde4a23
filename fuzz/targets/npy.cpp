// SPDX-License-Identifier: BSD-3-Clause
// NumPy .npy: the in-memory header parser, then the file reader (mapped, C or Fortran order).
#include "fuzz/targets/volume_readers.h"
#include "sources/readers/npy_reader.h"

namespace voxlink::fuzz {

Status fuzzNpy(Input input) {
  auto header = sources::parseNpyHeader(input.data(), input.size(), "input.npy");
  Status opened = openAndDrain(input, "input.npy", sources::openNpy);
  // The parser and the reader must agree on whether the header is acceptable.
  if (!header && opened) return header.status();
  return opened;
}

}  // namespace voxlink::fuzz
