// SPDX-License-Identifier: BSD-3-Clause
#include "fuzz/targets/volume_readers.h"

namespace voxlink::fuzz {

Status openAndDrain(Input input, const std::string& mainName, const OpenFn& open,
                    const sources::OpenOptions& options, bool openDir) {
  const std::string path = scratch().write(splitFuzzFiles(input, mainName));
  auto source = open(openDir ? scratch().path().string() : path, options);
  if (!source) return source.status();
  return drainVolume(**source);
}

bool startsWithGzip(Input input) {
  return input.size() >= 2 && input[0] == 0x1f && input[1] == 0x8b;
}

bool startsWithZip(Input input) { return input.size() >= 2 && input[0] == 'P' && input[1] == 'K'; }

}  // namespace voxlink::fuzz
