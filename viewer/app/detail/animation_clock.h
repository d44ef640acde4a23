// SPDX-License-Identifier: BSD-3-Clause
// The viewer's animation time for a dynamic scene (docs/dynamic-scenes.md): it runs with the
// wall clock while playing and loops over the scene's span; the panel pauses it and sets it.
// Free of GL and GLFW so tests can drive it.
#pragma once

namespace voxlink::viewer {

class AnimationClock {
 public:
  // `span` > 0 seconds (SceneDescription::animationSpan); the clock starts at 0, playing.
  explicit AnimationClock(double span);
  double time() const { return time_; }
  double span() const { return span_; }
  bool playing() const { return playing_; }
  void setPlaying(bool playing) { playing_ = playing; }
  // Sets the time, wrapped into [0, span) (a non-finite time is ignored).
  void setTime(double seconds);
  // Advances by `dtSeconds` of wall clock when playing (negative or non-finite steps count as
  // 0). Returns whether the time changed.
  bool advance(double dtSeconds);

 private:
  double span_ = 1, time_ = 0;
  bool playing_ = true;
};

}  // namespace voxlink::viewer
