// VTK XML image data: inline or appended data, base64 or raw, zlib blocks.
#include "fuzz/targets/volume_readers.h"
#include "sources/readers/vti_reader.h"

namespace voxlink::fuzz {

Status fuzzVti(Input input) { return openAndDrain(input, "input.vti", convert::openVti); }

}  // namespace voxlink::fuzz
