#include "convert/readers/reader_registry.h"

#include <algorithm>
#include <filesystem>

#include "convert/readers/raw_reader.h"

namespace voxlink::convert {

std::string lowerExtension(const std::string& path) {
  std::string name = std::filesystem::path(path).filename().string();
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  const bool gz = name.size() > 3 && name.ends_with(".gz");
  if (gz) name.resize(name.size() - 3);
  const auto dot = name.rfind('.');
  std::string ext = dot == std::string::npos ? "" : name.substr(dot);
  return gz ? ext + ".gz" : ext;
}

const std::vector<ReaderEntry>& readerRegistry() {
  static const std::vector<ReaderEntry> registry = [] {
    std::vector<ReaderEntry> r;
    auto hasExt = [](std::vector<std::string> exts) {
      return [exts = std::move(exts)](const std::string& path) {
        const std::string ext = lowerExtension(path);
        return std::find(exts.begin(), exts.end(), ext) != exts.end();
      };
    };
    r.push_back({"raw", hasExt({".raw", ".bin", ".img8", ".u8", ".u16", ".f32", ".f64"}), openRaw});
    return r;
  }();
  return registry;
}

}  // namespace voxlink::convert
