// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/reader_registry.h"

#include <algorithm>
#include <filesystem>

#include "sources/readers/detail/dicom_probe.h"
#include "sources/readers/dicom_reader.h"
#include "sources/readers/dicom_series.h"
#include "sources/readers/gslib_reader.h"
#include "sources/readers/image_stack_reader.h"
#include "sources/readers/metaimage_reader.h"
#include "sources/readers/nifti_reader.h"
#include "sources/readers/npy_reader.h"
#include "sources/readers/nrrd_reader.h"
#include "sources/readers/raw_reader.h"
#include "sources/readers/reader_common.h"
#include "sources/readers/vdb_reader.h"
#include "sources/readers/vti_reader.h"
#include "sources/readers/vvd_reader.h"

namespace voxlink::sources {

std::string lowerExtension(const std::string& path) {
  std::string name = std::filesystem::path(path).filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return std::tolower(c); });
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
    const auto isDir = [](const std::string& path) {
      std::error_code ec;
      return std::filesystem::is_directory(path, ec);
    };
    // Names first, then content: a NRRD without its extension still starts with "NRRD000".
    r.push_back({"nrrd",
                 [hasExt](const std::string& p) {
                   return hasExt({".nrrd", ".nhdr"})(p) || fileStartsWith(p, "NRRD000");
                 },
                 openNrrd});
    r.push_back({"metaimage", hasExt({".mhd", ".mha"}), openMetaImage});
    r.push_back({"nifti", hasExt({".nii", ".nii.gz"}), openNifti});
    r.push_back({"vvd", hasExt({".vvd"}), openVvd});
    r.push_back({"vdb", hasExt({".vdb"}), openVdb});
    r.push_back({"vti", hasExt({".vti"}), openVti, true});
    // Folders: DICOM when they hold DICOM files, else a stack of slice images. One DICOM file
    // (multi-frame, or a single image) is a volume too.
    r.push_back(
        {"dicom",
         [isDir](const std::string& p) { return isDir(p) ? folderHoldsDicom(p) : fileIsDicom(p); },
         openDicomSeries});
    r.push_back({"image-stack",
                 [isDir, hasExt](const std::string& p) {
                   return isDir(p) || hasExt({".tif", ".tiff"})(p);
                 },
                 openImageStack});
    r.push_back({"raw", hasExt({".raw", ".bin", ".img8", ".u8", ".u16", ".f32", ".f64"}), openRaw});
    r.push_back({"npy",
                 [](const std::string& path) {
                   return lowerExtension(path) == ".npy" || hasNpyMagic(path);
                 },
                 openNpy});
    r.push_back({"gslib", looksLikeGslib, openGslib, true});
    return r;
  }();
  return registry;
}

}  // namespace voxlink::sources
