// .vxl files: the cheap open (header, section table) and then the full validator, which must
// turn every damaged file into an error. A file that validates is walked like a viewer would.
#include "format/validator.h"
#include "format/voxlink_file.h"
#include "fuzz/fuzz_targets.h"

namespace voxlink::fuzz {

Status fuzzVxl(Input input) {
  auto file = format::VoxLinkFile::fromBytes({input.begin(), input.end()}, "fuzz.vxl");
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
