// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/dicom_probe.h"

#include <fstream>
#include <string_view>

#include "sources/readers/detail/text_header.h"

namespace voxlink::sources {

namespace fs = std::filesystem;

bool looksLikeDicom(const fs::path& p) {
  if (p.filename() == "DICOMDIR") return false;  // an index, not an image
  if (toLower(p.extension().string()) == ".dcm") return true;
  std::ifstream in(p, std::ios::binary);
  char magic[132] = {};
  in.read(magic, sizeof magic);
  return in.gcount() == 132 && std::string_view(magic + 128, 4) == "DICM";
}

bool folderHoldsDicom(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return false;
  if (fs::is_regular_file(fs::path(dir) / "DICOMDIR", ec)) return true;  // a CD/PACS export
  // Exports nest their images in folders: look below, but at 64 files at most.
  int looked = 0;
  fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
  for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    if (looksLikeDicom(it->path())) return true;
    if (++looked >= 64) break;  // a folder of other files: stop early
  }
  return false;
}

bool fileIsDicom(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec) && looksLikeDicom(path);
}

}  // namespace voxlink::sources
