#include "convert/readers/reader_registry.h"

#include <algorithm>
#include <filesystem>

#include "convert/readers/gslib_reader.h"
#include "convert/readers/npy_reader.h"
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
    // The list is copied: an initializer_list's array dies with the full expression.
    auto hasExt = [](std::initializer_list<const char*> list) {
      return [exts = std::vector<std::string>(list.begin(), list.end())](const std::string& path) {
        const std::string ext = lowerExtension(path);
        return std::any_of(exts.begin(), exts.end(), [&](const std::string& e) { return ext == e; });
      };
    };
    r.push_back({"raw", hasExt({".raw", ".bin", ".img8", ".u8", ".u16", ".f32", ".f64"}), openRaw});
    r.push_back({"npy", [](const std::string& path) { return lowerExtension(path) == ".npy" || hasNpyMagic(path); }, openNpy});
    r.push_back({"gslib", looksLikeGslib, openGslib});
    return r;
  }();
  return registry;
}

}  // namespace voxlink::convert
