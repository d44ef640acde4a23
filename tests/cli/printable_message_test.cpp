// SPDX-License-Identifier: BSD-3-Clause
#include "cli/printable_message.h"

#include <gtest/gtest.h>

namespace voxlink::cli {
namespace {

TEST(PrintableMessage, KeepsTextAndUtf8EscapesTheRest) {
  EXPECT_EQ(printableMessage("plain text, 1.5 mm"), "plain text, 1.5 mm");
  EXPECT_EQ(printableMessage("K\xC3\xB6rper \xE2\x86\x92 \xF0\x9F\x98\x80"),
            "K\xC3\xB6rper \xE2\x86\x92 \xF0\x9F\x98\x80");
  EXPECT_EQ(printableMessage("a\nb\tc\rd"), "a\\nb\\tc\\rd");
  EXPECT_EQ(printableMessage(std::string("nul\0x", 5)), "nul\\x00x");
  EXPECT_EQ(printableMessage("\x1B[31m"), "\\x1B[31m");
  // Stray and truncated sequences, overlong forms and surrogates are bytes, not characters.
  EXPECT_EQ(printableMessage("Ima\xF6"
                             "e"),
            "Ima\\xF6e");
  EXPECT_EQ(printableMessage("\xE2\x86"), "\\xE2\\x86");
  EXPECT_EQ(printableMessage("\xC0\xAF"), "\\xC0\\xAF");
  EXPECT_EQ(printableMessage("\xED\xA0\x80"), "\\xED\\xA0\\x80");
  EXPECT_EQ(printableMessage("\x7F"), "\\x7F");
}

}  // namespace
}  // namespace voxlink::cli
