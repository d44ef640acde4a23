// SPDX-License-Identifier: BSD-3-Clause
// .vxl files: the cheap open (header, section table) and then the full validator, which must
// turn every damaged file into an error. A file that validates is walked like a viewer would.
// Packed files (magic "VOXLINKZ") are unpacked first, with at most 256 MiB unpacked (the
// command line allows 64 GiB; libFuzzer's memory limit is 2 GB).
#include "format/validator.h"
#include "format/voxlink_file.h"
#include "fuzz/fuzz_targets.h"
#include "pack/open_file.h"
#include "pack/packed_file.h"

namespace voxlink::fuzz {

Status fuzzVxl(Input input) {
  auto file = pack::isPackedFile(input)
                  ? pack::unpackFile(input, "fuzz.vxl", uint64_t{256} << 20)
                  : pack::fileFromBytes({input.begin(), input.end()}, "fuzz.vxl");
  if (!file) return file.status();
  auto report = format::validateFile(*file);
  if (!report) return report.status();
  // Valid: every voxel value and the metadata must be readable.
  volatile double sum = 0;
  for (uint64_t i = 0; i < file->voxelCount(); ++i) sum = sum + file->value(i);
  (void)file->metaJson();
  return Status::ok();
}

}  // namespace voxlink::fuzz
