// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/text_header.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>

#include "base/regular_file.h"

namespace voxlink::sources {

std::string_view trim(std::string_view text) {
  const auto isSpace = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
  while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
  return text;
}

std::string toLower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::vector<std::string> splitWords(std::string_view text) {
  std::vector<std::string> words;
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    size_t j = i;
    while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j]))) ++j;
    if (j > i) words.emplace_back(text.substr(i, j - i));
    i = j;
  }
  return words;
}

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

Result<std::string> readFilePrefix(const std::string& path, size_t maxBytes) {
  return base::readRegularFilePrefix(path, maxBytes);  // never blocks on a FIFO
}

std::optional<std::string_view> LineCursor::next(bool acceptUnterminated) {
  if (pos_ >= text_.size()) return std::nullopt;
  const size_t nl = text_.find('\n', pos_);
  if (nl == std::string_view::npos && !acceptUnterminated) return std::nullopt;
  const size_t end = nl == std::string_view::npos ? text_.size() : nl;
  std::string_view line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = nl == std::string_view::npos ? text_.size() : nl + 1;
  return line;
}

Error badField(const std::string& file, std::string_view field, std::string_view expected,
               std::string_view got) {
  return makeError(ErrorCode::kCorrupt, file, ": header field '", field, "': expected ", expected,
                   ", got '", got, "'");
}

namespace {

std::string expectation(std::optional<size_t> count, const char* what, const char* one) {
  if (!count) return what;
  if (*count == 1) return one;
  return cat(*count, " ", what);
}

template <class T>
Result<std::vector<T>> parseNumbers(std::string_view text, const std::string& file,
                                    std::string_view field, std::optional<size_t> count,
                                    const char* what, const char* one) {
  std::vector<T> values;
  for (const std::string& word : splitWords(text)) {
    T v{};
    const char* begin = word.data();
    const char* end = word.data() + word.size();
    if (!word.empty() && word[0] == '+') ++begin;  // from_chars refuses a leading '+'
    auto [ptr, ec] = std::from_chars(begin, end, v);
    if (ec != std::errc() || ptr != end) {
      return badField(file, field, expectation(count, what, one), trim(text));
    }
    values.push_back(v);
  }
  if (count && values.size() != *count)
    return badField(file, field, expectation(count, what, one), trim(text));
  return values;
}

}  // namespace

Result<std::vector<double>> parseDoubles(std::string_view text, const std::string& file,
                                         std::string_view field, std::optional<size_t> count) {
  return parseNumbers<double>(text, file, field, count, "numbers", "a number");
}

Result<std::vector<int64_t>> parseIntegers(std::string_view text, const std::string& file,
                                           std::string_view field, std::optional<size_t> count) {
  return parseNumbers<int64_t>(text, file, field, count, "integers", "an integer");
}

Result<int64_t> parseInteger(std::string_view text, const std::string& file,
                             std::string_view field) {
  VOXLINK_ASSIGN_OR_RETURN(std::vector<int64_t> v, parseIntegers(text, file, field, 1));
  return v[0];
}

Result<bool> parseBool(std::string_view text, const std::string& file, std::string_view field) {
  const std::string_view t = trim(text);
  if (equalsIgnoreCase(t, "true")) return true;
  if (equalsIgnoreCase(t, "false")) return false;
  return badField(file, field, "True or False", t);
}

}  // namespace voxlink::sources
