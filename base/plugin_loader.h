// SPDX-License-Identifier: BSD-3-Clause
// Loading VoxLink's plugins: the pieces that pull in heavy libraries (OpenImageIO, OpenVDB,
// GDCM) are shared modules loaded on first use, so that a command which needs none of them
// starts in a few milliseconds instead of a third of a second.
#pragma once

#include <string>

#include "base/error.h"

namespace voxlink {
inline namespace base {

// The folder beside the Python module where `pip install` puts the plugins (setup.py).
inline constexpr const char* kPipPluginFolder = "voxlink.plugins";

// Loads `fileName` (e.g. "libvoxlink_vdb.so") once per process and returns the address of its
// `entry` symbol. Looks in $VOXLINK_PLUGIN_DIR, in voxlink.plugins beside the executable or
// Python module holding this code (a pip install), next to the executable, in
// <exe>/../lib/voxlink, in the build tree and in the install prefix, in that order.
Result<void*> pluginEntry(const std::string& fileName, const char* entry);

// A plugin's entry is a function returning a pointer to its table of functions (`Api`, a struct
// of function pointers; see sources/plugin_api.h). Loads the plugin on first use.
template <class Api>
Result<const Api*> pluginApi(const std::string& fileName, const char* entry) {
  VOXLINK_ASSIGN_OR_RETURN(void* e, pluginEntry(fileName, entry));
  return reinterpret_cast<const Api* (*)()>(e)();
}

}  // namespace base
}  // namespace voxlink
