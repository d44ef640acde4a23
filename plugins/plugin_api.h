// The entry points of the converter's plugins (see plugins/plugin_loader.h for why they are
// plugins). Both sides are built together, so C++ types cross the boundary safely.
#pragma once

#include <memory>
#include <string>

#include "sources/volume_source.h"
#include "format/footprint.h"
#include "format/voxlink_file.h"

namespace voxlink::convert {

struct DicomPluginApi {
  Result<std::unique_ptr<VolumeSource>> (*openSeries)(const std::string& dir, const OpenOptions& options);
};

struct VdbPluginApi {
  Result<std::unique_ptr<VolumeSource>> (*open)(const std::string& path, const OpenOptions& options);
  Result<format::PeerFootprint> (*measureFootprint)(const format::VoxLinkFile& file);
};

inline constexpr const char* kDicomPlugin = "libvoxlink_dicom.so";
inline constexpr const char* kDicomPluginEntry = "voxlink_dicom_plugin";
inline constexpr const char* kVdbPlugin = "libvoxlink_vdb.so";
inline constexpr const char* kVdbPluginEntry = "voxlink_vdb_plugin";

}  // namespace voxlink::convert
