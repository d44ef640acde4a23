// DICOM series from a folder (GDCM 3): one file per z slice, ordered by position along the
// slice normal, RescaleSlope/RescaleIntercept applied.
#pragma once

#include <memory>
#include <string>

#include "sources/volume_source.h"

namespace voxlink::convert {

// Through the DICOM plugin (libvoxlink_dicom.so, GDCM), loaded on first use.
Result<std::unique_ptr<VolumeSource>> openDicomSeries(const std::string& dir,
                                                      const OpenOptions& options);
// The implementation inside the plugin.
Result<std::unique_ptr<VolumeSource>> openDicomSeriesDirect(const std::string& dir,
                                                            const OpenOptions& options);

}  // namespace voxlink::convert
