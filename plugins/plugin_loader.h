// Loading VoxLink's plugins: the pieces that pull in heavy libraries (OpenImageIO, OpenVDB,
// GDCM) are shared modules loaded on first use, so that a command which needs none of them
// starts in a few milliseconds instead of a third of a second.
#pragma once

#include <string>

#include "format/error.h"

namespace voxlink::plugins {

// Loads `fileName` (e.g. "libvoxlink_vdb.so") once per process and returns the address of its
// `entry` symbol. Looks in $VOXLINK_PLUGIN_DIR, next to the executable, in <exe>/../lib/voxlink,
// in the build tree and in the install prefix, in that order.
Result<void*> pluginEntry(const std::string& fileName, const char* entry);

// Where `fileName` was loaded from (after a successful pluginEntry()).
std::string pluginLocation(const std::string& fileName);

}  // namespace voxlink::plugins
