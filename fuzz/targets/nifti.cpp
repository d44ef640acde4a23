// SPDX-License-Identifier: BSD-3-Clause
// NIfTI-1/2 single files; a gzip stream (magic 1f 8b) is named .nii.gz so it is decompressed.
#include "fuzz/targets/volume_readers.h"
#include "sources/readers/nifti_reader.h"

namespace voxlink::fuzz {

Status fuzzNifti(Input input) {
  return openAndDrain(input, startsWithGzip(input) ? "input.nii.gz" : "input.nii",
                      sources::openNifti);
}

}  // namespace voxlink::fuzz
