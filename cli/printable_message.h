// SPDX-License-Identifier: BSD-3-Clause
// Error messages quote what a damaged file holds; before printing, control characters and
// bytes that are not UTF-8 are escaped so every message stays one readable line.
#pragma once

#include <string>
#include <string_view>

namespace voxlink::cli {

// Valid UTF-8 passes through; \n, \r and \t become "\n", "\r" and "\t"; other control
// characters and stray bytes become "\xNN".
std::string printableMessage(std::string_view text);

}  // namespace voxlink::cli
