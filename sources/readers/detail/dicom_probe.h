// SPDX-License-Identifier: BSD-3-Clause
// Recognizing DICOM files without a DICOM library (so the registry can route folders without
// loading the DICOM plugin).
#pragma once

#include <filesystem>
#include <string>

namespace voxlink::sources {

// A .dcm file, or a file with "DICM" at byte 128 (DICOMDIR, an index, is not an image).
bool looksLikeDicom(const std::filesystem::path& p);
// True when the folder holds a DICOMDIR or DICOM files, in it or below it (looks at up to 64
// files).
bool folderHoldsDicom(const std::string& dir);
// True for one DICOM file (a multi-frame file is a volume by itself).
bool fileIsDicom(const std::string& path);

}  // namespace voxlink::sources
