// SPDX-License-Identifier: BSD-3-Clause
// The function tables of the readers' plugins (see base/plugin_loader.h for why there are
// plugins; imageio_plugin_api.h has the image plugin's). Every plugin has one entry, an
// extern "C" function returning a pointer to its table of plain functions; clients get it with
// plugins::pluginApi<Table>(file, entry). Both sides are built together with the same compiler
// and standard library, so C++ types cross the boundary safely.
#pragma once

#include <memory>
#include <string>

#include "format/voxlink_file.h"
#include "sources/readers/dicom_series.h"
#include "sources/volume_source.h"

namespace voxlink::sources {

// libvoxlink_dicom.so: DICOM series with GDCM (sources/readers/dicom_reader.h).
struct DicomPluginApi {
  Result<std::unique_ptr<sources::VolumeSource>> (*openSeries)(const std::string& dir,
                                                               const sources::OpenOptions& options);
  Result<sources::DicomFolderListing> (*listSeries)(const std::string& path);
};
inline constexpr const char* kDicomPlugin = "libvoxlink_dicom.so";
inline constexpr const char* kDicomPluginEntry = "voxlink_dicom_plugin";

// libvoxlink_vdb.so: .vdb grids (sources/readers/vdb_reader.h). The same module serves the
// OpenVDB footprint peer and export to convert/ from a second entry (convert/vdb_plugin_api.h).
struct VdbPluginApi {
  Result<std::unique_ptr<sources::VolumeSource>> (*open)(const std::string& path,
                                                         const sources::OpenOptions& options);
};
inline constexpr const char* kVdbPlugin = "libvoxlink_vdb.so";
inline constexpr const char* kVdbPluginEntry = "voxlink_vdb_plugin";

}  // namespace voxlink::sources

// The entries (kDicomPluginEntry, kVdbPluginEntry), defined in plugins/dicom_plugin.cpp and
// plugins/vdb_plugin.cpp: the only symbols the plugins export.
extern "C" __attribute__((visibility("default"))) const voxlink::sources::DicomPluginApi*
voxlink_dicom_plugin();
extern "C" __attribute__((visibility("default"))) const voxlink::sources::VdbPluginApi*
voxlink_vdb_plugin();
