// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/detail/animation_clock.h"

#include <cmath>

namespace voxlink::viewer {

AnimationClock::AnimationClock(double span) : span_(std::isfinite(span) && span > 0 ? span : 1.0) {}

void AnimationClock::setTime(double seconds) {
  if (!std::isfinite(seconds)) return;
  time_ = std::fmod(seconds, span_);
  if (time_ < 0) time_ += span_;
  if (time_ >= span_) time_ = 0;  // fmod of a value just below a multiple can round up
}

bool AnimationClock::advance(double dtSeconds) {
  if (!playing_ || !std::isfinite(dtSeconds) || dtSeconds <= 0) return false;
  const double before = time_;
  setTime(time_ + dtSeconds);
  return time_ != before;
}

}  // namespace voxlink::viewer
