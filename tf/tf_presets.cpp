// SPDX-License-Identifier: BSD-3-Clause
#include "tf/tf_presets.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "base/limits.h"
#include "base/regular_file.h"

namespace voxlink::tf {
namespace {

// Presets in normalized positions t in [0, 1].
struct Preset {
  const char* name;
  std::vector<std::pair<double, double>> opacity;
  std::vector<std::pair<double, std::array<double, 3>>> color;
};

const std::vector<Preset>& presets() {
  static const std::vector<Preset> all = {
      {"ct-bone",
       {{0.0, 0.0}, {0.15, 0.05}, {0.45, 0.5}, {1.0, 0.9}},
       {{0.0, {0.55, 0.25, 0.15}},
        {0.3, {0.88, 0.64, 0.45}},
        {0.6, {0.98, 0.9, 0.75}},
        {1.0, {1.0, 1.0, 0.96}}}},
      {"ct-soft-tissue",
       {{0.0, 0.0}, {0.1, 0.02}, {0.35, 0.08}, {0.6, 0.4}, {1.0, 0.85}},
       {{0.0, {0.62, 0.2, 0.14}},
        {0.35, {0.9, 0.5, 0.38}},
        {0.6, {0.95, 0.85, 0.7}},
        {1.0, {1.0, 1.0, 1.0}}}},
      {"grayscale", {{0.0, 0.0}, {1.0, 0.6}}, {{0.0, {0.15, 0.15, 0.15}}, {1.0, {1.0, 1.0, 1.0}}}},
      {"cool-warm",
       {{0.0, 0.5}, {0.5, 0.05}, {1.0, 0.5}},
       {{0.0, {0.23, 0.3, 0.75}}, {0.5, {0.87, 0.87, 0.87}}, {1.0, {0.71, 0.016, 0.15}}}},
      {"emission-fire",
       {{0.0, 0.0}, {0.3, 0.05}, {1.0, 0.7}},
       {{0.0, {0.3, 0.0, 0.0}},
        {0.4, {0.9, 0.3, 0.0}},
        {0.75, {1.0, 0.8, 0.2}},
        {1.0, {1.0, 1.0, 0.9}}}},
  };
  return all;
}

double parseNumber(const nlohmann::json& j) {
  if (j.is_number()) return j.get<double>();
  return std::nan("");
}

// A preset's "Name": empty when absent, nullopt when it is not a string (json::value would throw).
std::optional<std::string> presetName(const nlohmann::json& preset) {
  const auto it = preset.find("Name");
  if (it == preset.end()) return std::string();
  if (!it->is_string()) return std::nullopt;
  return it->get<std::string>();
}

}  // namespace

std::vector<std::string> tfPresetNames() {
  std::vector<std::string> names;
  for (const Preset& p : presets()) names.push_back(p.name);
  return names;
}

Result<tf::TransferFunction> tfPreset(const std::string& name, double lo, double hi) {
  if (!(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi))
    return makeError(ErrorCode::kInvalidArgument, "transfer function preset '", name,
                     "': value range [", lo, ", ", hi, "] is empty");
  for (const Preset& p : presets()) {
    if (name != p.name) continue;
    tf::TransferFunction tf;
    tf.name = name;
    // (1 - t) lo + t hi: exact at both ends and finite even when hi - lo overflows.
    for (const auto& [t, a] : p.opacity) tf.opacity.push_back({(1 - t) * lo + t * hi, a});
    for (const auto& [t, c] : p.color) tf.color.push_back({(1 - t) * lo + t * hi, c});
    return tf;
  }
  std::string known;
  for (const auto& n : tfPresetNames()) known += (known.empty() ? "" : ", ") + n;
  return makeError(ErrorCode::kInvalidArgument, "transfer function preset '", name,
                   "' is not one of: ", known);
}

tf::TransferFunction defaultTransferFunction(const format::VoxLinkFile& file) {
  try {
    const auto meta = nlohmann::json::parse(file.metaJson());
    if (meta.contains("classification") && meta["classification"].contains("tf")) {
      auto tf = tf::parseTransferFunction(meta["classification"]["tf"].dump(), file.path());
      if (tf) return *tf;
    }
  } catch (const nlohmann::json::exception&) {
    // No usable META: fall through to the preset.
  }
  const auto [lo, hi] = displayRange(file.header().valueMin, file.header().valueMax);
  auto tf = tfPreset("ct-bone", lo, hi);
  return tf ? *tf : tf::TransferFunction{};  // unreachable: displayRange gives lo < hi
}

std::pair<double, double> displayRange(double lo, double hi) {
  if (!std::isfinite(lo) && !std::isfinite(hi)) return {0.0, 1.0};  // NaN range: no voxels
  if (!std::isfinite(lo)) lo = hi;
  if (!std::isfinite(hi)) hi = lo;
  if (lo > hi) std::swap(lo, hi);
  if (lo < hi) return {lo, hi};
  // One value: a width that still changes lo at its magnitude (1e20 + 1 == 1e20).
  const double width = std::max(1.0, std::abs(lo) * 1e-3);
  if (std::isfinite(lo + width)) return {lo, lo + width};
  return {lo - width, lo};
}

Result<tf::TransferFunction> parseParaViewPreset(const std::string& text, const std::string& where,
                                                 const ParaViewImport& options) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    return makeError(ErrorCode::kInvalidArgument, where, ": not valid JSON: ", e.what());
  }
  const nlohmann::json* preset = nullptr;
  if (j.is_object()) {
    preset = &j;
  } else if (j.is_array()) {
    for (const auto& p : j)
      if (p.is_object() && (options.name.empty() || presetName(p) == options.name)) {
        preset = &p;
        break;
      }
  }
  if (!preset)
    return makeError(ErrorCode::kInvalidArgument, where, ": no ParaView preset",
                     options.name.empty() ? "" : " named '" + options.name + "'");
  const std::optional<std::string> maybeName = presetName(*preset);
  if (!maybeName)
    return makeError(ErrorCode::kInvalidArgument, where,
                     ": field 'Name': ", preset->at("Name").type_name(), " is not a string");
  const std::string& name = *maybeName;
  if (!preset->contains("RGBPoints") || !(*preset)["RGBPoints"].is_array())
    return makeError(
        ErrorCode::kInvalidArgument, where, ": preset '", name,
        "': field 'RGBPoints' missing (indexed or annotation presets are not supported)");
  const auto& rgb = (*preset)["RGBPoints"];
  if (rgb.size() < 4 || rgb.size() % 4 != 0)
    return makeError(ErrorCode::kInvalidArgument, where, ": preset '", name,
                     "': field 'RGBPoints' must hold groups of 4 numbers (x, r, g, b), got ",
                     rgb.size());
  tf::TransferFunction tf;
  tf.name = name;
  for (size_t i = 0; i < rgb.size(); i += 4) {
    tf::ColorPoint c{parseNumber(rgb[i]),
                     {parseNumber(rgb[i + 1]), parseNumber(rgb[i + 2]), parseNumber(rgb[i + 3])}};
    if (!std::isfinite(c.value) ||
        std::any_of(c.rgb.begin(), c.rgb.end(), [](double x) { return !(x >= 0 && x <= 1); }))
      return makeError(ErrorCode::kInvalidArgument, where, ": preset '", name, "': RGBPoints[", i,
                       "..", i + 3, "] must be finite with r, g, b in [0, 1]");
    tf.color.push_back(c);
  }
  std::stable_sort(tf.color.begin(), tf.color.end(),
                   [](const auto& a, const auto& b) { return a.value < b.value; });
  const double x0 = tf.color.front().value, x1 = tf.color.back().value;
  if (preset->contains("Points") && (*preset)["Points"].is_array() &&
      !(*preset)["Points"].empty()) {
    const auto& pts = (*preset)["Points"];
    if (pts.size() % 4 != 0)
      return makeError(
          ErrorCode::kInvalidArgument, where, ": preset '", name,
          "': field 'Points' must hold groups of 4 numbers (x, alpha, midpoint, sharpness)");
    for (size_t i = 0; i < pts.size(); i += 4) {
      const double x = parseNumber(pts[i]), a = parseNumber(pts[i + 1]);
      if (!std::isfinite(x) || !(a >= 0 && a <= 1))
        return makeError(ErrorCode::kInvalidArgument, where, ": preset '", name, "': Points[", i,
                         "] must be finite with alpha in [0, 1]");
      tf.opacity.push_back({x, a});
    }
    std::stable_sort(tf.opacity.begin(), tf.opacity.end(),
                     [](const auto& a, const auto& b) { return a.value < b.value; });
  } else {
    tf.opacity = {{x0, 0.0}, {x1, 0.6}};
  }
  if (options.lo < options.hi && x0 < x1) {
    auto map = [&](double x) {
      return options.lo + (x - x0) / (x1 - x0) * (options.hi - options.lo);
    };
    for (auto& c : tf.color) c.value = map(c.value);
    for (auto& o : tf.opacity) o.value = map(o.value);
  }
  return tf;
}

Result<tf::TransferFunction> importParaViewPreset(const std::string& path,
                                                  const ParaViewImport& options) {
  VOXLINK_ASSIGN_OR_RETURN(
      std::string text,
      base::readRegularFile(path, limits::kMaxTransferFunctionBytes, "ParaView preset"));
  return parseParaViewPreset(text, path, options);
}

}  // namespace voxlink::tf
