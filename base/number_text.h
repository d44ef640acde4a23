// SPDX-License-Identifier: BSD-3-Clause
// The shortest text that reads back as the same double ("1000.0000001", "0.1", "1e-308"): for
// messages about values that differ beyond the 6 significant digits a stream prints by default
// ("values must not decrease (1000 after 1000)").
#pragma once

#include <charconv>
#include <string>

namespace voxlink {
inline namespace base {

inline std::string exactNumber(double value) {
  char text[32];  // the longest shortest form, "-2.2250738585072014e-308", is 24 characters
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

}  // namespace base
}  // namespace voxlink
