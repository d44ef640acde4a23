// SPDX-License-Identifier: BSD-3-Clause
// The viewer's animation clock (viewer/app/detail/animation_clock.h): it loops over the span,
// stops when paused, and ignores steps that are not time.
#include "viewer/app/detail/animation_clock.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene_description.h"

namespace voxlink::viewer {
namespace {

TEST(AnimationClock, RunsLoopsAndPauses) {
  AnimationClock clock(3.0);
  EXPECT_TRUE(clock.playing());
  EXPECT_EQ(clock.time(), 0.0);
  EXPECT_TRUE(clock.advance(1.25));
  EXPECT_DOUBLE_EQ(clock.time(), 1.25);
  EXPECT_TRUE(clock.advance(2.5));  // past the span: loops
  EXPECT_DOUBLE_EQ(clock.time(), 0.75);
  clock.setPlaying(false);
  EXPECT_FALSE(clock.advance(1.0));
  EXPECT_DOUBLE_EQ(clock.time(), 0.75);
  clock.setTime(-0.5);  // the slider or a caller: wrapped into [0, span)
  EXPECT_DOUBLE_EQ(clock.time(), 2.5);
  clock.setTime(6.0);
  EXPECT_DOUBLE_EQ(clock.time(), 0.0);
  clock.setPlaying(true);
  EXPECT_FALSE(clock.advance(-1.0));
  EXPECT_FALSE(clock.advance(std::nan("")));
  clock.setTime(INFINITY);
  EXPECT_DOUBLE_EQ(clock.time(), 0.0);
  EXPECT_DOUBLE_EQ(AnimationClock(0.0).span(), 1.0);  // no span: a second
}

TEST(AnimationClock, SpanIsTheLongestPeriodOrLastKey) {
  scene::SceneDescription d;
  EXPECT_DOUBLE_EQ(d.animationSpan(), 1.0);
  scene::SceneObject keyed;
  keyed.animation = scene::Animation{};
  keyed.animation->keys = {{0.0, {}, {}}, {2.0, {}, {}}};
  d.objects.push_back(keyed);
  EXPECT_DOUBLE_EQ(d.animationSpan(), 2.0);
  scene::SceneObject looped = keyed;
  looped.animation->period = 5.0;
  d.objects.push_back(looped);
  EXPECT_DOUBLE_EQ(d.animationSpan(), 5.0);
}

}  // namespace
}  // namespace voxlink::viewer
