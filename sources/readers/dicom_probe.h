// Recognizing DICOM files without a DICOM library (so the registry can route folders without
// loading the DICOM plugin).
#pragma once

#include <filesystem>
#include <string>

namespace voxlink::convert {

// A .dcm file, or a file with "DICM" at byte 128 (DICOMDIR, an index, is not an image).
bool looksLikeDicom(const std::filesystem::path& p);
// True when the folder holds DICOM files (looks at up to 64 files).
bool folderHoldsDicom(const std::string& dir);

}  // namespace voxlink::convert
