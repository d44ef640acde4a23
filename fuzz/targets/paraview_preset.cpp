// SPDX-License-Identifier: BSD-3-Clause
// ParaView colour-map presets (viewer core), as found, and stretched onto a value range.
#include "fuzz/fuzz_targets.h"
#include "tf/tf_presets.h"

namespace voxlink::fuzz {

Status fuzzParaViewPreset(Input input) {
  const std::string text(input.begin(), input.end());
  auto asIs = tf::parseParaViewPreset(text, "fuzz.json", {});
  if (!asIs) return asIs.status();
  auto stretched = tf::parseParaViewPreset(text, "fuzz.json", {"", -1000.0, 3000.0});
  if (!stretched) return stretched.status();
  volatile double sum = 0;
  for (double v : {-2000.0, 0.0, 1000.0, 5000.0})
    sum = sum + stretched->opacityAt(v) + stretched->colorAt(v)[1];
  return Status::ok();
}

}  // namespace voxlink::fuzz
