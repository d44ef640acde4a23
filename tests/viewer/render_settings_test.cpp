// SPDX-License-Identifier: BSD-3-Clause
// parseImageSize, fuzzed in process: random strings over the characters a size is made of (and
// a few that are not) either fail or are exactly "W" + 'x'/'X' + "H" with both sides in
// [1, 2^32 - 1] written in digits; accepted sizes round-trip.
#include "render/render_settings.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>

namespace voxlink::render {

namespace {

// The reference rule, written independently: digits only on each side of one x or X.
bool isSize(const std::string& s, uint64_t& w, uint64_t& h) {
  const size_t x = s.find_first_of("xX");
  if (x == std::string::npos || x == 0 || x + 1 == s.size()) return false;
  auto side = [](const std::string& t, uint64_t& v) {
    if (t.empty() || t.size() > 12) return false;
    v = 0;
    for (char c : t) {
      if (c < '0' || c > '9') return false;
      v = v * 10 + uint64_t(c - '0');
    }
    return v >= 1 && v <= UINT32_MAX;
  };
  return side(s.substr(0, x), w) && side(s.substr(x + 1), h);
}

TEST(ParseImageSize, RandomStringsAgreeWithTheDigitsOnlyRule) {
  std::mt19937 rng(7);
  const std::string alphabet = "0123456789xX -+e.\t";
  int accepted = 0;
  for (int i = 0; i < 200000; ++i) {
    std::string s;
    const int length = int(rng() % 14);
    for (int k = 0; k < length; ++k)
      s += alphabet[rng() % 10 < 7 ? rng() % 10 : rng() % alphabet.size()];
    if (rng() % 2) s.insert(rng() % (s.size() + 1), 1, rng() % 2 ? 'x' : 'X');
    uint64_t w = 0, h = 0;
    const bool expected = isSize(s, w, h);
    auto got = parseImageSize(s);
    ASSERT_EQ(bool(got), expected) << "'" << s << "'";
    if (!got) continue;
    ++accepted;
    EXPECT_EQ((*got)[0], w) << s;
    EXPECT_EQ((*got)[1], h) << s;
  }
  EXPECT_GT(accepted, 1000);  // the generator reaches the accepting side too
  EXPECT_FALSE(parseImageSize("4294967296x1"));
  EXPECT_TRUE(parseImageSize("4294967295x1"));
}

}  // namespace
}  // namespace voxlink::render
