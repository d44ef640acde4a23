// SPDX-License-Identifier: BSD-3-Clause
// NRRD, attached (.nrrd) or detached with data files given as extra files (one per slice, numbered
// or LIST).
#include "fuzz/targets/volume_readers.h"
#include "sources/readers/nrrd_reader.h"

namespace voxlink::fuzz {

Status fuzzNrrd(Input input) { return openAndDrain(input, "input.nrrd", sources::openNrrd); }

}  // namespace voxlink::fuzz
