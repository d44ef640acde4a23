// SPDX-License-Identifier: BSD-3-Clause
// Small text helpers shared by the hand-written header parsers (NRRD, MetaImage, Voreen .vvd):
// line splitting that keeps byte offsets, trimming, and number lists whose errors name the
// file, the field and the offending text.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"

namespace voxlink::sources {

std::string_view trim(std::string_view text);
std::string toLower(std::string_view text);
std::vector<std::string> splitWords(std::string_view text);
// Case-insensitive comparison for field names and enum words.
bool equalsIgnoreCase(std::string_view a, std::string_view b);

// Reads at most `maxBytes` from the start of `path` (a header and possibly some data after it).
Result<std::string> readFilePrefix(const std::string& path, size_t maxBytes);

// Walks a buffer line by line; accepts "\n" and "\r\n" endings.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text) : text_(text) {}
  // The next line without its ending, or nullopt at the end of the buffer. A last line without
  // a newline is returned only when `acceptUnterminated` is set.
  std::optional<std::string_view> next(bool acceptUnterminated = true);
  // Byte offset just after the line last returned (where the next line or the data begins).
  size_t offset() const { return pos_; }
  bool atEnd() const { return pos_ >= text_.size(); }

 private:
  std::string_view text_;
  size_t pos_ = 0;
};

// Parses whitespace-separated numbers. With `count` set, exactly that many are required.
// Errors: kCorrupt "<file>: header field '<field>': expected 3 numbers, got '<text>'".
Result<std::vector<double>> parseDoubles(std::string_view text, const std::string& file,
                                         std::string_view field,
                                         std::optional<size_t> count = std::nullopt);
Result<std::vector<int64_t>> parseIntegers(std::string_view text, const std::string& file,
                                           std::string_view field,
                                           std::optional<size_t> count = std::nullopt);

// A single integer / boolean ("True"/"False", case-insensitive) field value.
Result<int64_t> parseInteger(std::string_view text, const std::string& file,
                             std::string_view field);
Result<bool> parseBool(std::string_view text, const std::string& file, std::string_view field);

// The error every header parser returns for a malformed field value.
Error badField(const std::string& file, std::string_view field, std::string_view expected,
               std::string_view got);

}  // namespace voxlink::sources
