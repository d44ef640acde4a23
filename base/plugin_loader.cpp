// SPDX-License-Identifier: BSD-3-Clause
#include "base/plugin_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <vector>

namespace voxlink {
inline namespace base {
namespace {

struct Loaded {
  void* entry = nullptr;
  std::string error;
};

std::mutex mutex;
std::map<std::string, Loaded> loaded;

// The folder of the executable or shared object (the Python module) this code is linked into:
// a module installed by pip lives in a venv while /proc/self/exe names the system python3.
std::filesystem::path folderOfThisBinary() {
  Dl_info info{};
  if (!dladdr(reinterpret_cast<void*>(&folderOfThisBinary), &info) || !info.dli_fname ||
      !*info.dli_fname)
    return {};
  std::error_code ec;
  const auto path = std::filesystem::canonical(info.dli_fname, ec);
  return ec ? std::filesystem::path() : path.parent_path();
}

std::vector<std::filesystem::path> searchDirs() {
  std::vector<std::filesystem::path> dirs;
  if (const char* env = std::getenv("VOXLINK_PLUGIN_DIR")) dirs.emplace_back(env);
  if (const auto binary = folderOfThisBinary(); !binary.empty())
    dirs.push_back(binary / kPipPluginFolder);
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    dirs.push_back(exe.parent_path());
    dirs.push_back((exe.parent_path() / ".." / "lib" / "voxlink").lexically_normal());
  }
#ifdef VOXLINK_PLUGIN_BUILD_DIR
  dirs.emplace_back(VOXLINK_PLUGIN_BUILD_DIR);
#endif
#ifdef VOXLINK_PLUGIN_INSTALL_DIR
  dirs.emplace_back(VOXLINK_PLUGIN_INSTALL_DIR);
#endif
  return dirs;
}

Loaded load(const std::string& fileName, const char* entry) {
  Loaded result;
  std::string tried;
  for (const auto& dir : searchDirs()) {
    const std::string path = (dir / fileName).string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
      tried += (tried.empty() ? "" : ", ") + dir.string();
      continue;
    }
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed
    if (!handle) {
      result.error = cat(path, ": cannot load plugin: ", dlerror());
      return result;
    }
    result.entry = dlsym(handle, entry);
    if (!result.entry) result.error = cat(path, ": not a VoxLink plugin (no ", entry, ")");
    return result;
  }
  result.error = cat(fileName, " (built with VoxLink) was not found in ", tried,
                     "; set VOXLINK_PLUGIN_DIR to the folder that holds it");
  return result;
}

}  // namespace

Result<void*> pluginEntry(const std::string& fileName, const char* entry) {
  std::lock_guard lock(mutex);
  auto it = loaded.find(fileName);
  if (it == loaded.end()) it = loaded.emplace(fileName, load(fileName, entry)).first;
  if (!it->second.entry) return makeError(ErrorCode::kUnsupported, it->second.error);
  return it->second.entry;
}

}  // namespace base
}  // namespace voxlink
