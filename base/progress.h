// SPDX-License-Identifier: BSD-3-Clause
// How a long library call tells its caller how far it got, for a CLI's progress bar: the
// fraction of the work done (0 to 1) and the stage it is in. Libraries never print; a caller
// that does not want progress passes an empty callback. Called at coarse steps (a section, a
// layer of bricks), so it costs nothing measurable.
#pragma once

#include <functional>

namespace voxlink {
inline namespace base {

using ProgressCallback = std::function<void(double fraction, const char* stage)>;

inline void reportProgress(const ProgressCallback& progress, double fraction, const char* stage) {
  if (progress) progress(fraction, stage);
}

// The part [begin, end] of `whole`: a step reports 0 to 1 of its own work into a larger bar.
inline ProgressCallback progressPart(const ProgressCallback& whole, double begin, double end) {
  if (!whole) return {};
  return [whole, begin, end](double fraction, const char* stage) {
    whole(begin + (end - begin) * fraction, stage);
  };
}

}  // namespace base
}  // namespace voxlink
