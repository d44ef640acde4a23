// SPDX-License-Identifier: BSD-3-Clause
#include "convert/batch.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <system_error>

namespace voxlink::convert {
namespace fs = std::filesystem;

std::string batchOutputName(const std::string& input) {
  std::string name = fs::path(input).lexically_normal().filename().string();
  if (name.empty()) name = fs::path(input).lexically_normal().parent_path().filename().string();
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
  if (lower.size() > 3 && lower.ends_with(".gz")) name.resize(name.size() - 3);
  const size_t dot = name.rfind('.');
  if (dot != std::string::npos && dot > 0) name.resize(dot);
  return name + ".vxl";
}

namespace {

uint64_t inputBytes(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) {
    const uint64_t size = fs::file_size(path, ec);
    return ec ? 0 : size;
  }
  uint64_t total = 0;
  for (auto it = fs::recursive_directory_iterator(path, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
    if (it->is_regular_file(ec)) total += it->file_size(ec);
  return total;
}

}  // namespace

Result<std::vector<BatchItem>> readBatchList(const std::string& listPath,
                                             const std::string& outDir) {
  std::ifstream in(listPath);
  if (!in) return makeError(ErrorCode::kIo, listPath, ": cannot open the batch list");
  const fs::path base = fs::path(listPath).parent_path();
  std::vector<BatchItem> items;
  std::map<std::string, uint64_t> lineOfOutput;
  std::string text;
  for (uint64_t line = 1; std::getline(in, text); ++line) {
    while (!text.empty() && (text.back() == '\r' || text.back() == ' ' || text.back() == '\t'))
      text.pop_back();
    const size_t start = text.find_first_not_of(" \t");
    if (start == std::string::npos || text[start] == '#') continue;
    fs::path input = text.substr(start);
    if (input.is_relative() && !base.empty()) input = base / input;
    std::error_code ec;
    if (!fs::exists(input, ec))
      return makeError(ErrorCode::kIo, listPath, ":", line, ": ", input.string(),
                       ": no such file or folder");
    BatchItem item;
    item.input = input.string();
    item.output = (fs::path(outDir) / batchOutputName(item.input)).string();
    item.bytes = inputBytes(input);
    item.line = line;
    if (auto [at, fresh] = lineOfOutput.emplace(item.output, line); !fresh)
      return makeError(ErrorCode::kInvalidArgument, listPath, ":", line, ": ", item.input,
                       " would write ", item.output, ", as line ", at->second, " does");
    items.push_back(std::move(item));
  }
  if (in.bad()) return makeError(ErrorCode::kIo, listPath, ": read failed");
  std::stable_sort(items.begin(), items.end(),
                   [](const BatchItem& a, const BatchItem& b) { return a.bytes > b.bytes; });
  return items;
}

}  // namespace voxlink::convert
