// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/particle_loader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <unordered_map>

namespace voxlink::geometry {
namespace {

struct BondiRadius {
  const char* element;
  float radius;
};

// Bondi, "van der Waals Volumes and Radii", J. Phys. Chem. 68 (1964) 441-451, Table I.
constexpr BondiRadius kBondi[] = {
    {"H", 1.20f},  {"He", 1.40f}, {"Li", 1.82f}, {"C", 1.70f},  {"N", 1.55f},  {"O", 1.52f},
    {"F", 1.47f},  {"Ne", 1.54f}, {"Na", 2.27f}, {"Mg", 1.73f}, {"Si", 2.10f}, {"P", 1.80f},
    {"S", 1.80f},  {"Cl", 1.75f}, {"Ar", 1.88f}, {"K", 2.75f},  {"Ni", 1.63f}, {"Cu", 1.40f},
    {"Zn", 1.39f}, {"Ga", 1.87f}, {"As", 1.85f}, {"Se", 1.90f}, {"Br", 1.85f}, {"Kr", 2.02f},
    {"Pd", 1.63f}, {"Ag", 1.72f}, {"Cd", 1.58f}, {"In", 1.93f}, {"Sn", 2.17f}, {"Te", 2.06f},
    {"I", 1.98f},  {"Xe", 2.16f}, {"Pt", 1.72f}, {"Au", 1.66f}, {"Hg", 1.55f}, {"Tl", 1.96f},
    {"Pb", 2.02f}, {"U", 1.86f},
};

// "fe" / "FE" -> "Fe".
std::string canonicalElement(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (std::isalpha(static_cast<unsigned char>(c)))
      out.push_back(static_cast<char>(out.empty() ? std::toupper(static_cast<unsigned char>(c))
                                                  : std::tolower(static_cast<unsigned char>(c))));
  }
  return out;
}

// "file: line N", formatted only when an error message needs it.
struct Where {
  const std::string& path;
  size_t line;
};
std::ostream& operator<<(std::ostream& out, const Where& where) {
  return out << where.path << ": line " << where.line;
}

class MaterialTable {
 public:
  Result<uint16_t> index(const std::string& name, const Where& where) {
    auto it = ids_.find(name);
    if (it != ids_.end()) return it->second;
    if (names_.size() >= 65536)
      return makeError(ErrorCode::kTooLarge, where, ": more than 65536 materials");
    const auto id = static_cast<uint16_t>(names_.size());
    ids_.emplace(name, id);
    names_.push_back(name);
    return id;
  }
  std::vector<std::string> take() { return std::move(names_); }

 private:
  std::unordered_map<std::string, uint16_t> ids_;
  std::vector<std::string> names_;
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// Parses the whole of `field` as a float (leading '+' allowed; "nan" and "inf" parse, the
// callers reject them with their own message).
bool parseFloat(std::string_view field, float& value) {
  field = trim(field);
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  if (field.empty()) return false;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
  return ec == std::errc() && end == field.data() + field.size();
}

// PDB convention for the atom name (columns 13-16): one-letter elements start in column 14
// (" CA " is an alpha carbon); two-letter elements fill 13-14 and nothing follows ("CA  " is
// calcium, "FE  " iron); a four-character name starting in column 13 is a hydrogen ("HG21").
std::string elementFromAtomName(std::string name) {
  name.resize(4, ' ');
  auto alpha = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; };
  if (!alpha(name[0])) {
    for (size_t i = 1; i < 4; ++i)
      if (alpha(name[i])) return canonicalElement(name.substr(i, 1));
    return {};
  }
  if (alpha(name[1]) && name[2] == ' ' && name[3] == ' ')
    return canonicalElement(name.substr(0, 2));
  return canonicalElement(name.substr(0, 1));
}

Result<std::ifstream> openText(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    return makeError(ErrorCode::kIo, path,
                     std::filesystem::exists(path, ec)
                         ? ": not a regular file (a directory, FIFO or device)"
                         : ": no such file");
  std::ifstream in(path);
  if (!in) return makeError(ErrorCode::kIo, path, ": cannot open");
  return in;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

float vanDerWaalsRadius(std::string_view element) {
  const std::string symbol = canonicalElement(element);
  for (const BondiRadius& entry : kBondi)
    if (symbol == entry.element) return entry.radius;
  return 0.0f;
}

Result<ParticleSet> loadPdb(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(std::ifstream in, openText(path));
  ParticleSet set;
  MaterialTable materials;
  std::string line;
  static constexpr const char* kAxes[] = {"x (columns 31-38)", "y (columns 39-46)",
                                          "z (columns 47-54)"};
  for (size_t number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("ATOM", 0) != 0 && line.rfind("HETATM", 0) != 0) continue;
    const Where where{path, number};
    if (line.size() < 54) {
      return makeError(ErrorCode::kTruncated, where, ": ", line.substr(0, 6), " record has ",
                       line.size(), " columns, the coordinates need 54");
    }
    Sphere sphere;
    for (int axis = 0; axis < 3; ++axis) {
      const std::string_view field = std::string_view(line).substr(30 + 8 * axis, 8);
      if (!parseFloat(field, sphere.center[axis])) {
        return makeError(ErrorCode::kCorrupt, where, ": ", kAxes[axis], ": '", trim(field),
                         "' is not a number");
      }
      if (!std::isfinite(sphere.center[axis])) {
        return makeError(ErrorCode::kNonFinite, where, ": ", kAxes[axis], ": '", trim(field),
                         "' is not finite");
      }
    }
    std::string element = line.size() >= 78 ? canonicalElement(line.substr(76, 2)) : std::string();
    if (element.empty()) element = elementFromAtomName(line.substr(12, 4));
    if (element.empty()) {
      return makeError(ErrorCode::kCorrupt, where,
                       ": no element in columns 77-78 or in the atom name");
    }
    const float radius = vanDerWaalsRadius(element);
    sphere.radius = radius > 0.0f ? radius : kDefaultVdwRadius;
    VOXLINK_ASSIGN_OR_RETURN(sphere.material, materials.index(element, where));
    set.spheres.push_back(sphere);
  }
  if (set.spheres.empty())
    return makeError(ErrorCode::kCorrupt, path, ": no ATOM or HETATM records");
  set.materials = materials.take();
  return set;
}

Result<ParticleSet> loadParticleText(const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(std::ifstream in, openText(path));
  ParticleSet set;
  MaterialTable materials;
  static constexpr const char* kFields[] = {"x", "y", "z", "r"};
  std::string line;
  bool firstRecord = true;
  for (size_t number = 1; std::getline(in, line); ++number) {
    std::string_view text = line;
    if (const size_t hash = text.find('#'); hash != std::string_view::npos)
      text = text.substr(0, hash);
    std::vector<std::string_view> fields;
    size_t start = 0;
    while (start < text.size()) {
      const size_t end = text.find_first_of(", \t\r", start);
      const size_t stop = end == std::string_view::npos ? text.size() : end;
      if (stop > start) fields.push_back(text.substr(start, stop - start));
      start = stop + 1;
    }
    if (fields.empty()) continue;
    const Where where{path, number};
    float probe = 0.0f;
    if (firstRecord && !parseFloat(fields[0], probe)) {  // a header line
      firstRecord = false;
      continue;
    }
    firstRecord = false;
    if (fields.size() < 4 || fields.size() > 5) {
      return makeError(ErrorCode::kCorrupt, where, ": ", fields.size(),
                       " fields, expected x y z r [material]");
    }
    Sphere sphere;
    float values[4];
    for (int f = 0; f < 4; ++f) {
      if (!parseFloat(fields[f], values[f]))
        return makeError(ErrorCode::kCorrupt, where, ": field '", kFields[f], "': '", fields[f],
                         "' is not a number");
      if (!std::isfinite(values[f]))
        return makeError(ErrorCode::kNonFinite, where, ": field '", kFields[f], "': '", fields[f],
                         "' is not finite");
    }
    if (values[3] <= 0.0f) {
      return makeError(ErrorCode::kInvalidArgument, where, ": field 'r': ", fields[3],
                       " is not a positive radius");
    }
    sphere.center = {values[0], values[1], values[2]};
    sphere.radius = values[3];
    VOXLINK_ASSIGN_OR_RETURN(
        sphere.material,
        materials.index(fields.size() == 5 ? std::string(fields[4]) : "default", where));
    set.spheres.push_back(sphere);
  }
  if (set.spheres.empty()) return makeError(ErrorCode::kCorrupt, path, ": no spheres");
  set.materials = materials.take();
  return set;
}

Result<ParticleSet> loadParticles(const std::string& path) {
  const std::string extension = lower(std::filesystem::path(path).extension().string());
  if (extension == ".pdb" || extension == ".ent") return loadPdb(path);
  return loadParticleText(path);
}

}  // namespace voxlink::geometry
