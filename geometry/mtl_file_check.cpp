// SPDX-License-Identifier: BSD-3-Clause
// The MTL statements that crash assimp 5.2.5 (docs/fuzzing.md, "mesh"): its MTL importer writes
// texture maps and anisotropy into the current material without checking that there is one, and
// there is none before the first `newmtl` (the OBJ sets none before its `mtllib`). The other
// statements (Kd, Ns, d, illum, ...) it skips there. The check walks the statements as assimp
// does: a statement starts the file or follows a line end ('\n', '\r', '\f' or NUL) and the
// spaces and tabs after it, and assimp picks its handler by the first byte alone (case
// sensitive), then compares the texture keywords ignoring case. A UTF-8 byte order mark assimp
// drops before reading (BaseImporter::TextFileToBuffer), so the statement after it opens the file.
#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string_view>

#include "geometry/detail/mesh_file_checks.h"

namespace voxlink::geometry {
namespace {

bool isLineEnd(char c) { return c == '\n' || c == '\r' || c == '\f' || c == '\0'; }

bool startsWithIgnoringCase(std::string_view text, std::string_view prefix) {
  return text.size() >= prefix.size() &&
         std::equal(prefix.begin(), prefix.end(), text.begin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) ==
                  std::tolower(static_cast<unsigned char>(b));
         });
}

// The texture keywords assimp 5.2.5 stores into the current material (`refl` it ignores).
constexpr std::array<std::string_view, 16> kTextureKeywords = {
    "map_Kd",   "map_Ka", "map_Ks", "map_disp", "disp",   "map_d",  "map_emissive", "map_Ke",
    "map_bump", "bump",   "map_Kn", "norm",     "map_ns", "map_Pr", "map_Pm",       "map_Ps"};

// Whether assimp hands the statement to its texture reader: by the first byte `m`, `b`, `d`
// followed by "isp", or `n`/`N` followed by `o`; then a keyword must match.
bool isTextureStatement(std::string_view s) {
  const bool dispatched = s.starts_with('m') || s.starts_with('b') || s.starts_with("disp") ||
                          s.starts_with("no") || s.starts_with("No");
  if (!dispatched) return false;
  return std::any_of(kTextureKeywords.begin(), kTextureKeywords.end(),
                     [&](std::string_view k) { return startsWithIgnoringCase(s, k); });
}

// The statement's keyword as the error shows it: up to the first blank, printable bytes only.
std::string keywordOf(std::string_view s) {
  std::string word;
  for (char c : s) {
    if (c == ' ' || c == '\t' || isLineEnd(c) || word.size() == 32) break;
    word += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  }
  return word;
}

// The line an editor shows for byte `at`: "\n", "\r\n" and a lone "\r" each end one.
size_t lineNumberAt(std::string_view text, size_t at) {
  size_t line = 1;
  for (size_t i = 0; i < at; ++i)
    if (text[i] == '\n' || (text[i] == '\r' && (i + 1 >= text.size() || text[i + 1] != '\n')))
      ++line;
  return line;
}

}  // namespace

Status checkMtlFile(const std::string& path, const std::string& objPath) {
  // A device or FIFO (`mtllib /dev/zero`) would never end; assimp sees it as empty.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return Status::ok();
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::ok();  // assimp reports what it cannot open
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string_view all(text);
  if (all.starts_with("\xEF\xBB\xBF")) all.remove_prefix(3);
  size_t at = 0;
  while (at < all.size()) {
    // assimp skips the blanks after a line end, not those that open the file.
    while (at > 0 && at < all.size() && (all[at] == ' ' || all[at] == '\t')) ++at;
    const std::string_view statement = all.substr(at);
    // `newmtl` to assimp is an `n` or `N` followed by `e`; from then on a material is current.
    if (statement.size() >= 2 && (statement[0] == 'n' || statement[0] == 'N') &&
        statement[1] == 'e')
      return Status::ok();
    const bool anisotropy = statement.starts_with('a');
    if (anisotropy || isTextureStatement(statement)) {
      return makeError(ErrorCode::kCorrupt, path, ": line ", lineNumberAt(all, at), ": '",
                       keywordOf(statement), "' ", anisotropy ? "(anisotropy) " : "(texture map) ",
                       "before the first newmtl belongs to no material (material library of ",
                       objPath, ")");
    }
    while (at < all.size() && !isLineEnd(all[at])) ++at;
    if (at < all.size()) ++at;
  }
  return Status::ok();
}

}  // namespace voxlink::geometry
