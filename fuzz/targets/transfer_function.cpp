// SPDX-License-Identifier: BSD-3-Clause
// The TF JSON (docs/transfer-function.md); an accepted TF is evaluated the way the converter
// and the viewer use it.
#include "tf/transfer_function.h"

#include "fuzz/targets/volume_readers.h"

namespace voxlink::fuzz {

Status fuzzTransferFunction(Input input) {
  const std::string text(input.begin(), input.end());
  auto tf = tf::parseTransferFunction(text, "fuzz.json");
  if (!tf) return tf.status();
  volatile double sum = 0;
  for (const auto& interval : tf->visibleIntervals()) {
    sum = sum + tf->opacityAt(interval.lo) + tf->colorAt(interval.hi)[0];
  }
  // Written back and read again, a TF must survive unchanged in shape.
  auto again = tf::parseTransferFunction(tf::transferFunctionJson(*tf), "again.json");
  if (!again) return again.status();
  return Status::ok();
}

}  // namespace voxlink::fuzz
