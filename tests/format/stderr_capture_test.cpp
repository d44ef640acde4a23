// SPDX-License-Identifier: BSD-3-Clause
// Library chatter on stderr is captured while a StderrCapture lives, and only then.
#include "base/stderr_capture.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>

namespace voxlink {
namespace {

TEST(StderrCapture, CapturesTheFirstLineAndRestoresStderr) {
  const int before = ::dup(2);
  {
    StderrCapture outer;
    std::fprintf(stderr, "\n** ERROR: first complaint\nsecond line\n");
    {
      StderrCapture inner;  // nested: shares the outer redirection
      std::fputs("third\n", stderr);
    }
    EXPECT_EQ(outer.firstLine(), "** ERROR: first complaint");
  }
  {
    StderrCapture quiet;
    EXPECT_EQ(quiet.firstLine(), "");
  }
  // fd 2 points where it pointed before.
  struct stat a {
  }, b{};
  ASSERT_EQ(fstat(before, &a), 0);
  ASSERT_EQ(fstat(2, &b), 0);
  EXPECT_EQ(a.st_ino, b.st_ino);
  EXPECT_EQ(a.st_dev, b.st_dev);
  ::close(before);
}

}  // namespace
}  // namespace voxlink
