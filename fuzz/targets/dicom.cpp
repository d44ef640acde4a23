// SPDX-License-Identifier: BSD-3-Clause
// DICOM series: the input's files form the folder (main file input.dcm); the in-plugin reader
// is called directly, so GDCM still runs first in the forked child of its guard.
#include "fuzz/targets/volume_readers.h"
#include "sources/readers/dicom_reader.h"

namespace voxlink::fuzz {

Status fuzzDicom(Input input) {
  return openAndDrain(input, "input.dcm", sources::openDicomSeriesDirect, {}, true);
}

}  // namespace voxlink::fuzz
