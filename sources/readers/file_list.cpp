// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/file_list.h"

#include <cctype>
#include <filesystem>

#include "base/checked_math.h"
#include "base/limits.h"
#include "sources/readers/detail/text_header.h"

namespace voxlink::sources {
namespace {

struct NumberFormat {
  std::string prefix;
  std::string suffix;
  bool zeroPad = false;
  size_t width = 0;
};

Result<NumberFormat> parseNumberFormat(const std::string& pattern, const std::string& file,
                                       std::string_view field) {
  NumberFormat f;
  bool seen = false;
  std::string* out = &f.prefix;
  for (size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') {
      *out += pattern[i];
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      *out += '%';
      ++i;
      continue;
    }
    size_t j = i + 1;
    if (j < pattern.size() && pattern[j] == '0') {
      f.zeroPad = true;
      ++j;
    }
    while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j]))) {
      f.width = f.width * 10 + static_cast<size_t>(pattern[j] - '0');
      if (f.width > 32) return badField(file, field, "a field width up to 32", pattern);
      ++j;
    }
    if (seen || j >= pattern.size() ||
        (pattern[j] != 'd' && pattern[j] != 'i' && pattern[j] != 'u'))
      return badField(file, field, "a file name format with one %d", pattern);
    seen = true;
    out = &f.suffix;
    i = j;
  }
  if (!seen) return badField(file, field, "a file name format with one %d", pattern);
  return f;
}

std::string formatNumber(const NumberFormat& f, int64_t value) {
  std::string digits =
      value < 0 ? std::to_string(uint64_t{0} - uint64_t(value)) : std::to_string(value);
  const size_t body = digits.size() + (value < 0 ? 1 : 0);
  std::string padded;
  if (body < f.width) padded.assign(f.width - body, f.zeroPad ? '0' : ' ');
  if (value < 0) return f.prefix + (f.zeroPad ? "-" + padded : padded + "-") + digits + f.suffix;
  return f.prefix + padded + digits + f.suffix;
}

}  // namespace

Result<std::vector<std::string>> expandNumberedFiles(const std::vector<std::string>& words,
                                                     const std::string& file,
                                                     std::string_view field) {
  if (words.size() != 4)
    return badField(file, field, "'<format> <min> <max> <step>'", [&] {
      std::string s;
      for (const auto& w : words) s += (s.empty() ? "" : " ") + w;
      return s;
    }());
  VOXLINK_ASSIGN_OR_RETURN(NumberFormat format, parseNumberFormat(words[0], file, field));
  VOXLINK_ASSIGN_OR_RETURN(int64_t first, parseInteger(words[1], file, field));
  VOXLINK_ASSIGN_OR_RETURN(int64_t last, parseInteger(words[2], file, field));
  VOXLINK_ASSIGN_OR_RETURN(int64_t step, parseInteger(words[3], file, field));
  if (step == 0 || (step > 0 && last < first) || (step < 0 && last > first))
    return badField(file, field, "a step that walks from min to max",
                    cat(words[1], " ", words[2], " ", words[3]));
  // |last - first| / |step| in unsigned arithmetic: the int64 difference and INT64_MIN / -1
  // both overflow.
  const uint64_t span =
      last >= first ? uint64_t(last) - uint64_t(first) : uint64_t(first) - uint64_t(last);
  const uint64_t stride = step > 0 ? uint64_t(step) : uint64_t{0} - uint64_t(step);
  const uint64_t count = span / stride + 1;
  if (span / stride >= limits::kMaxListedFiles)
    return makeError(ErrorCode::kTooLarge, file, ": header field '", field, "': ", span / stride,
                     " + 1 files listed, more than ", limits::kMaxListedFiles);
  std::vector<std::string> names;
  names.reserve(static_cast<size_t>(count));
  // first + i * step stays between first and last, so it fits in int64.
  for (uint64_t i = 0; i < count; ++i)
    names.push_back(formatNumber(format, int64_t(uint64_t(first) + i * uint64_t(step))));
  return names;
}

Status appendNumberedFiles(const std::vector<std::string>& words, const std::string& headerPath,
                           std::string_view field, std::vector<std::string>& paths) {
  VOXLINK_ASSIGN_OR_RETURN(std::vector<std::string> names,
                           expandNumberedFiles(words, headerPath, field));
  for (const auto& n : names) paths.push_back(besideHeader(headerPath, n));
  return Status::ok();
}

std::string besideHeader(const std::string& headerPath, const std::string& name) {
  const std::filesystem::path p(name);
  if (p.is_absolute()) return name;
  return (std::filesystem::path(headerPath).parent_path() / p).lexically_normal().string();
}

bool naturalLess(std::string_view a, std::string_view b) {
  size_t i = 0, j = 0;
  const auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  while (i < a.size() && j < b.size()) {
    if (digit(a[i]) && digit(b[j])) {
      size_t ie = i, je = j;
      while (ie < a.size() && digit(a[ie])) ++ie;
      while (je < b.size() && digit(b[je])) ++je;
      // Compare by value: strip leading zeros, then longer is bigger, then lexicographic.
      size_t is = i, js = j;
      while (is + 1 < ie && a[is] == '0') ++is;
      while (js + 1 < je && b[js] == '0') ++js;
      const std::string_view na = a.substr(is, ie - is), nb = b.substr(js, je - js);
      if (na.size() != nb.size()) return na.size() < nb.size();
      if (na != nb) return na < nb;
      // Same value: fewer leading zeros first, so the order is total.
      if (ie - i != je - j) return ie - i < je - j;
      i = ie;
      j = je;
    } else {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

}  // namespace voxlink::sources
