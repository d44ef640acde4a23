// SPDX-License-Identifier: BSD-3-Clause
#include "render/recorded_source.h"

#include <filesystem>
#include <nlohmann/json.hpp>

namespace voxlink::render {
namespace {

namespace fs = std::filesystem;

// OpenOptions from the recorded JSON; unknown keys are ignored, bad ones reported.
Result<sources::OpenOptions> parseOptions(const nlohmann::json& j, const std::string& where) {
  sources::OpenOptions o;
  if (!j.is_object()) return o;
  try {
    if (j.contains("dims") && j["dims"].is_array() && j["dims"].size() == 3)
      o.dims = std::array<uint32_t, 3>{j["dims"][0].get<uint32_t>(), j["dims"][1].get<uint32_t>(),
                                       j["dims"][2].get<uint32_t>()};
    if (j.contains("type") && j["type"].is_string()) {
      const auto type = parseScalarName(j["type"].get<std::string>());
      if (!type)
        return makeError(ErrorCode::kCorrupt, where,
                         ": META field 'source.open_options.type': unknown type '",
                         j["type"].get<std::string>(), "'");
      o.type = *type;
    }
    if (j.contains("endian") && j["endian"].is_string())
      o.endian = j["endian"].get<std::string>() == "big" ? sources::Endian::kBig
                                                         : sources::Endian::kLittle;
    if (j.contains("header_bytes") && j["header_bytes"].is_number_unsigned())
      o.headerBytes = j["header_bytes"].get<uint64_t>();
    if (j.contains("spacing") && j["spacing"].is_array() && j["spacing"].size() == 3)
      o.spacing =
          std::array<double, 3>{j["spacing"][0].get<double>(), j["spacing"][1].get<double>(),
                                j["spacing"][2].get<double>()};
    if (j.contains("format") && j["format"].is_string()) o.format = j["format"].get<std::string>();
  } catch (const nlohmann::json::exception& e) {
    return makeError(ErrorCode::kCorrupt, where, ": META field 'source.open_options': ", e.what());
  }
  return o;
}

}  // namespace

Result<RecordedSource> recordedSource(const format::VoxLinkFile& file) {
  nlohmann::json meta;
  try {
    meta = nlohmann::json::parse(file.metaJson());
  } catch (const nlohmann::json::exception& e) {
    return makeError(ErrorCode::kCorrupt, file.path(), ": META is not valid JSON: ", e.what());
  }
  if (!meta.contains("source") || !meta["source"].is_object() || !meta["source"].contains("path") ||
      !meta["source"]["path"].is_string())
    return makeError(ErrorCode::kInvalidArgument, file.path(),
                     ": META records no source path; give the source volume explicitly");
  const auto& source = meta["source"];
  RecordedSource r;
  r.path = source["path"].get<std::string>();
  VOXLINK_ASSIGN_OR_RETURN(
      r.options, parseOptions(source.value("open_options", nlohmann::json::object()), file.path()));
  if (r.options.format.empty() && source.contains("format") && source["format"].is_string() &&
      source["format"].get<std::string>() == "raw")
    r.options.format = "raw";
  std::error_code ec;
  if (!fs::exists(r.path, ec)) {
    const fs::path beside = fs::path(file.path()).parent_path() / r.path;
    if (fs::path(r.path).is_relative() && fs::exists(beside, ec)) {
      r.path = beside.string();
    } else {
      return makeError(ErrorCode::kIo, file.path(), ": recorded source '", r.path,
                       "' not found (neither from here nor beside the file)");
    }
  }
  return r;
}

Result<RecordedSource> chosenSource(const format::VoxLinkFile& file,
                                    const std::string& overridePath,
                                    const sources::OpenOptions& options) {
  if (overridePath.empty()) return recordedSource(file);
  return RecordedSource{overridePath, options};
}

Result<DenseVolume> loadSourceVolume(const format::VoxLinkFile& file,
                                     const std::string& overridePath,
                                     const sources::OpenOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(RecordedSource source, chosenSource(file, overridePath, options));
  const std::string& path = source.path;
  VOXLINK_ASSIGN_OR_RETURN(DenseVolume v, loadDenseVolume(path, source.options));
  const auto& h = file.header();
  if (v.dims[0] != h.dims[0] || v.dims[1] != h.dims[1] || v.dims[2] != h.dims[2])
    return makeError(ErrorCode::kSizeMismatch, path, ": source dims ", v.dims[0], "x", v.dims[1],
                     "x", v.dims[2], " differ from ", file.path(), "'s ", h.dims[0], "x", h.dims[1],
                     "x", h.dims[2]);
  // The file's geometry is what the GL renderer uses; the reference must use the same.
  for (int a = 0; a < 3; ++a) {
    v.spacing[a] = h.spacing[a];
    v.origin[a] = h.origin[a];
  }
  return v;
}

}  // namespace voxlink::render
