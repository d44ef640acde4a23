#include "sources/readers/dicom_probe.h"

#include <fstream>
#include <string_view>

#include "sources/readers/text_header.h"

namespace voxlink::convert {

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
  int looked = 0;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (!entry.is_regular_file(ec)) continue;
    if (looksLikeDicom(entry.path())) return true;
    if (++looked >= 64) break;  // a folder of other files: stop early
  }
  return false;
}

}  // namespace voxlink::convert
