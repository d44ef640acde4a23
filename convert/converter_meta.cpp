// SPDX-License-Identifier: BSD-3-Clause
#include "convert/detail/converter_meta.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <system_error>

namespace voxlink::convert {

using sources::Endian;
using sources::OpenOptions;
using sources::VolumeInfo;

namespace {

constexpr const char* kGradientMethod =
    "central differences of source values per world unit, one-sided at the volume border";

nlohmann::ordered_json sourceJson(const VolumeInfo& info, const OpenOptions& open) {
  std::error_code ec;
  const auto absolute = std::filesystem::absolute(info.path, ec);
  nlohmann::ordered_json j;
  j["path"] = ec ? info.path : absolute.lexically_normal().string();
  j["format"] = info.format;
  j["type"] = std::string(scalarName(info.type));
  j["dims"] = info.dims;
  j["spacing"] = info.spacing;
  j["origin"] = info.origin;
  j["notes"] = info.notes;
  if (const auto& r = info.rescale)  // only rescaling readers: other files' META is unchanged
    j["rescale"] = {{"field", r->field},
                    {"stored_type", r->storedType},
                    {"slope", {r->minSlope, r->maxSlope}},
                    {"intercept", {r->minIntercept, r->maxIntercept}}};
  nlohmann::ordered_json o;
  if (!open.format.empty()) o["format"] = open.format;
  if (open.dims) o["dims"] = *open.dims;
  if (open.type) o["type"] = std::string(scalarName(*open.type));
  if (open.type || open.dims) o["endian"] = open.endian == Endian::kLittle ? "little" : "big";
  if (open.headerBytes) o["header_bytes"] = open.headerBytes;
  if (open.spacing) o["spacing"] = *open.spacing;
  j["open_options"] = o.empty() ? nlohmann::ordered_json::object() : o;
  return j;
}

}  // namespace

std::string metaJson(const VolumeInfo& info, const ConvertOptions& options,
                     const ValueMapping& mapping, const ConvertSummary& s) {
  nlohmann::ordered_json j;
  j["generator"] = "voxlink 0.1.0";
  j["source"] = sourceJson(info, options.sourceOptions);
  j["classification"] = classificationToJson(options.classification);
  j["bricks"] = {{"size", options.brickSize},
                 {"predominant_axis", std::string(1, "xyz"[static_cast<int>(options.axis)])}};
  j["values"] = {{"stored_type", std::string(storedName(mapping.type))},
                 {"scale", mapping.scale},
                 {"offset", mapping.offset},
                 {"choice", mapping.reason},
                 {"error_bound", mapping.errorBound},
                 {"max_abs_error", s.valueMaxAbsError},
                 {"max_rel_error", s.valueMaxRelError}};
  j["gradients"] = {{"method", kGradientMethod},
                    {"codec", "polar16"},
                    {"zero", s.zeroGradients},
                    {"error_deg",
                     {{"mean", s.gradientMeanErrorDeg},
                      {"max", s.gradientMaxErrorDeg},
                      {"samples", s.gradientSamples},
                      {"sample_stride", options.errorSampleStride}}}};
  return j.dump(2);
}

}  // namespace voxlink::convert
