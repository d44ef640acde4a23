// SPDX-License-Identifier: BSD-3-Clause
#include "convert/classification.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

namespace voxlink::convert {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Result<double> parseNumber(const std::string& text, const std::string& what) {
  double v = 0;
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  while (begin < end && *begin == ' ') ++begin;
  auto [ptr, ec] = std::from_chars(begin, end, v);
  if (ec != std::errc() || ptr != end || !std::isfinite(v))
    return makeError(ErrorCode::kInvalidArgument, what, ": '", text, "' is not a finite number");
  return v;
}

nlohmann::json boundToJson(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

Result<double> boundFromJson(const nlohmann::json& j, const char* field) {
  if (j.is_number()) return j.get<double>();
  if (j.is_string() && j.get<std::string>() == "inf") return kInf;
  if (j.is_string() && j.get<std::string>() == "-inf") return -kInf;
  return makeError(ErrorCode::kCorrupt, "classification.keep.", field,
                   ": expected a number, \"inf\" or \"-inf\"");
}

}  // namespace

bool Classification::keeps(double v) const {
  if (kind == Kind::kAll) return true;
  if (mean && sigma) v = (v - *mean) / *sigma;
  return tf::anyContains(keep, v);
}

std::string Classification::describe() const {
  switch (kind) {
    case Kind::kAll:
      return "keep all";
    case Kind::kThreshold:
      return "threshold " + tf::describeIntervals(keep);
    case Kind::kTransferFunction:
      return "transfer function opacity > 0 on " + tf::describeIntervals(keep);
    case Kind::kKeepOutside:
      return std::string("keep ") +
             (mean && sigma ? cat("z = (v - ", *mean, ") / ", *sigma, " in ") : "") +
             tf::describeIntervals(keep);
  }
  return "";
}

Result<Classification> thresholdClassification(const std::vector<std::string>& specs) {
  Classification c;
  c.kind = Classification::Kind::kThreshold;
  for (const std::string& spec : specs) {
    const auto comma = spec.find(',');
    const std::string what = "--threshold " + spec;
    if (comma == std::string::npos) {
      VOXLINK_ASSIGN_OR_RETURN(double lo, parseNumber(spec, what));
      c.keep.push_back({lo, kInf, false, true});
    } else {
      VOXLINK_ASSIGN_OR_RETURN(double lo, parseNumber(spec.substr(0, comma), what));
      VOXLINK_ASSIGN_OR_RETURN(double hi, parseNumber(spec.substr(comma + 1), what));
      if (hi < lo)
        return makeError(ErrorCode::kInvalidArgument, what, ": upper bound ", hi,
                         " is below lower bound ", lo);
      c.keep.push_back({lo, hi, false, false});
    }
  }
  if (c.keep.empty())
    return makeError(ErrorCode::kInvalidArgument, "--threshold: no interval given");
  return c;
}

Classification tfClassification(const tf::TransferFunction& tf) {
  Classification c;
  c.kind = Classification::Kind::kTransferFunction;
  c.keep = tf.visibleIntervals();
  c.tf = tf;
  return c;
}

Result<Classification> keepOutsideClassification(double lo, double hi, std::optional<double> mean,
                                                 std::optional<double> sigma) {
  if (!(lo <= hi) || !std::isfinite(lo) || !std::isfinite(hi))
    return makeError(ErrorCode::kInvalidArgument, "--keep-outside ", lo, ",", hi,
                     ": expected finite LO <= HI");
  if (sigma && !(*sigma > 0 && std::isfinite(*sigma)))
    return makeError(ErrorCode::kInvalidArgument, "--sigma ", *sigma,
                     ": expected a finite value > 0");
  if (mean && !std::isfinite(*mean))
    return makeError(ErrorCode::kInvalidArgument, "--mean ", *mean, ": expected a finite value");
  if (mean.has_value() != sigma.has_value())
    return makeError(ErrorCode::kInvalidArgument,
                     "--keep-outside: give both mean and sigma to standardize, or neither");
  Classification c;
  c.kind = Classification::Kind::kKeepOutside;
  c.keep = {{-kInf, lo, true, true}, {hi, kInf, true, true}};
  c.mean = mean;
  c.sigma = sigma;
  return c;
}

Classification keepAllClassification() { return Classification{}; }

nlohmann::json classificationToJson(const Classification& c) {
  nlohmann::ordered_json j;
  switch (c.kind) {
    case Classification::Kind::kAll:
      j["kind"] = "all";
      break;
    case Classification::Kind::kThreshold:
      j["kind"] = "threshold";
      break;
    case Classification::Kind::kTransferFunction:
      j["kind"] = "transfer-function";
      break;
    case Classification::Kind::kKeepOutside:
      j["kind"] = "keep-outside";
      break;
  }
  j["keep"] = nlohmann::ordered_json::array();
  for (const tf::ValueInterval& i : c.keep)
    j["keep"].push_back({{"lo", boundToJson(i.lo)},
                         {"hi", boundToJson(i.hi)},
                         {"lo_open", i.loOpen},
                         {"hi_open", i.hiOpen}});
  if (c.mean && c.sigma) j["standardize"] = {{"mean", *c.mean}, {"sigma", *c.sigma}};
  if (c.tf) j["tf"] = nlohmann::json::parse(tf::transferFunctionJson(*c.tf));
  j["description"] = c.describe();
  return j;
}

Result<Classification> classificationFromJson(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("kind") || !j["kind"].is_string())
    return makeError(ErrorCode::kCorrupt, "classification.kind: missing");
  Classification c;
  const std::string kind = j["kind"].get<std::string>();
  if (kind == "all")
    c.kind = Classification::Kind::kAll;
  else if (kind == "threshold")
    c.kind = Classification::Kind::kThreshold;
  else if (kind == "transfer-function")
    c.kind = Classification::Kind::kTransferFunction;
  else if (kind == "keep-outside")
    c.kind = Classification::Kind::kKeepOutside;
  else
    return makeError(ErrorCode::kCorrupt, "classification.kind: unknown '", kind, "'");
  if (j.contains("keep")) {
    for (const auto& i : j["keep"]) {
      tf::ValueInterval interval{};
      VOXLINK_ASSIGN_OR_RETURN(interval.lo, boundFromJson(i.value("lo", nlohmann::json()), "lo"));
      VOXLINK_ASSIGN_OR_RETURN(interval.hi, boundFromJson(i.value("hi", nlohmann::json()), "hi"));
      interval.loOpen = i.value("lo_open", false);
      interval.hiOpen = i.value("hi_open", false);
      c.keep.push_back(interval);
    }
  }
  if (j.contains("standardize")) {
    c.mean = j["standardize"].value("mean", 0.0);
    c.sigma = j["standardize"].value("sigma", 1.0);
  }
  if (j.contains("tf")) {
    VOXLINK_ASSIGN_OR_RETURN(tf::TransferFunction tf,
                             tf::parseTransferFunction(j["tf"].dump(), "classification.tf"));
    c.tf = std::move(tf);
  }
  return c;
}

}  // namespace voxlink::convert
