// SPDX-License-Identifier: BSD-3-Clause
#include "tf/transfer_function.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/limits.h"
#include "base/number_text.h"
#include "base/output_file.h"
#include "base/regular_file.h"

namespace voxlink::tf {
namespace {

template <class Point, class Get>
auto interpolate(const std::vector<Point>& points, double value, Get get) {
  using R = decltype(get(points.front()));
  if (points.empty()) return R{};
  if (value < points.front().value) return get(points.front());
  if (value >= points.back().value) return get(points.back());
  auto hi = std::upper_bound(points.begin(), points.end(), value,
                             [](double v, const Point& p) { return v < p.value; });
  auto lo = hi - 1;
  const double span = hi->value - lo->value;
  const double t = span > 0 ? (value - lo->value) / span : 1.0;
  const R a = get(*lo), b = get(*hi);
  if constexpr (std::is_same_v<R, double>) {
    return a + (b - a) * t;
  } else {
    R r{};
    for (size_t i = 0; i < r.size(); ++i) r[i] = a[i] + (b[i] - a[i]) * t;
    return r;
  }
}

}  // namespace

double TransferFunction::opacityAt(double value) const {
  return interpolate(opacity, value, [](const OpacityPoint& p) { return p.alpha; });
}

std::array<double, 3> TransferFunction::colorAt(double value) const {
  return interpolate(color, value, [](const ColorPoint& p) { return p.rgb; });
}

std::vector<ValueInterval> TransferFunction::visibleIntervals() const {
  std::vector<ValueInterval> out;
  if (opacity.empty()) return out;
  const double inf = std::numeric_limits<double>::infinity();
  // Adds an interval, merging it with the previous one when they touch.
  auto add = [&](double lo, double hi, bool loOpen, bool hiOpen) {
    if (!out.empty() && out.back().hi == lo && (!out.back().hiOpen || !loOpen)) {
      out.back().hi = hi;
      out.back().hiOpen = hiOpen;
    } else {
      out.push_back({lo, hi, loOpen, hiOpen});
    }
  };
  // Opacity is linear between neighbouring distinct values; at a value given twice (a step)
  // the last point holds, as in opacityAt(). So: open pieces between distinct values, and
  // each distinct value on its own.
  if (opacity.front().alpha > 0) add(-inf, opacity.front().value, true, true);
  for (size_t i = 0; i < opacity.size(); ++i) {
    const double v = opacity[i].value;
    if (i + 1 < opacity.size() && opacity[i + 1].value == v) continue;  // not the last of a step
    if (opacity[i].alpha > 0) add(v, v, false, false);
    if (i + 1 < opacity.size() && (opacity[i].alpha > 0 || opacity[i + 1].alpha > 0))
      add(v, opacity[i + 1].value, true, true);
  }
  if (opacity.back().alpha > 0) add(opacity.back().value, inf, true, true);
  return out;
}

Result<TransferFunction> parseTransferFunction(const std::string& text, const std::string& where) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    return makeError(ErrorCode::kInvalidArgument, where, ": not valid JSON: ", e.what());
  }
  if (!j.is_object() || !j.contains("opacity"))
    return makeError(ErrorCode::kInvalidArgument, where,
                     ": field 'opacity': missing (a VoxLink transfer function is an object with "
                     "'opacity' and 'color' point lists)");
  // The two fields the writer stamps: a file of another format or a newer version is refused
  // rather than read as if it were this one (both may be left out).
  if (j.contains("format") && j["format"] != "voxlink-transfer-function")
    return makeError(ErrorCode::kInvalidArgument, where, ": field 'format': ", j["format"].dump(),
                     " (expected \"voxlink-transfer-function\")");
  if (j.contains("version") && j["version"] != 1)
    return makeError(ErrorCode::kInvalidArgument, where, ": field 'version': ", j["version"].dump(),
                     " (this reader knows version 1)");
  TransferFunction tf;
  if (j.contains("name")) {
    if (!j["name"].is_string())
      return makeError(ErrorCode::kInvalidArgument, where, ": field 'name': expected a string");
    tf.name = j["name"].get<std::string>();
  }
  const auto& op = j["opacity"];
  if (!op.is_array() || op.empty())
    return makeError(ErrorCode::kInvalidArgument, where,
                     ": field 'opacity': expected a non-empty array of [value, alpha]");
  for (size_t i = 0; i < op.size(); ++i) {
    const auto& p = op[i];
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      return makeError(ErrorCode::kInvalidArgument, where, ": field 'opacity[", i,
                       "]': expected [value, alpha]");
    const double v = p[0].get<double>(), a = p[1].get<double>();
    if (!std::isfinite(v) || !(a >= 0 && a <= 1))
      return makeError(ErrorCode::kInvalidArgument, where, ": field 'opacity[", i,
                       "]': value must be finite and alpha in [0, 1], got [", exactNumber(v), ", ",
                       exactNumber(a), "]");
    if (!tf.opacity.empty() && v < tf.opacity.back().value)
      return makeError(ErrorCode::kInvalidArgument, where, ": field 'opacity[", i,
                       "]': values must not decrease (", exactNumber(v), " after ",
                       exactNumber(tf.opacity.back().value), ")");
    tf.opacity.push_back({v, a});
  }
  if (j.contains("color")) {
    const auto& col = j["color"];
    if (!col.is_array())
      return makeError(ErrorCode::kInvalidArgument, where,
                       ": field 'color': expected an array of [value, r, g, b]");
    for (size_t i = 0; i < col.size(); ++i) {
      const auto& p = col[i];
      if (!p.is_array() || p.size() != 4)
        return makeError(ErrorCode::kInvalidArgument, where, ": field 'color[", i,
                         "]': expected [value, r, g, b]");
      ColorPoint c{};
      for (size_t k = 0; k < 4; ++k) {
        if (!p[k].is_number())
          return makeError(ErrorCode::kInvalidArgument, where, ": field 'color[", i, "]': element ",
                           k, " is not a number");
        const double x = p[k].get<double>();
        if (!std::isfinite(x) || (k > 0 && (x < 0 || x > 1)))
          return makeError(ErrorCode::kInvalidArgument, where, ": field 'color[", i,
                           "]': value must be finite and r, g, b in [0, 1]");
        if (k == 0)
          c.value = x;
        else
          c.rgb[k - 1] = x;
      }
      if (!tf.color.empty() && c.value < tf.color.back().value)
        return makeError(ErrorCode::kInvalidArgument, where, ": field 'color[", i,
                         "]': values must not decrease (", exactNumber(c.value), " after ",
                         exactNumber(tf.color.back().value), ")");
      tf.color.push_back(c);
    }
  }
  if (tf.color.empty()) tf.color = {{tf.opacity.front().value, {1, 1, 1}}};
  return tf;
}

Result<TransferFunction> loadTransferFunction(const std::string& path) {
  // A FIFO or device must fail at once, not block the command (regular files only).
  VOXLINK_ASSIGN_OR_RETURN(
      std::string text,
      readRegularFile(path, limits::kMaxTransferFunctionBytes, "transfer function"));
  return parseTransferFunction(text, path);
}

std::string transferFunctionJson(const TransferFunction& tf) {
  nlohmann::ordered_json j;
  j["format"] = "voxlink-transfer-function";
  j["version"] = 1;
  if (!tf.name.empty()) j["name"] = tf.name;
  j["opacity"] = nlohmann::ordered_json::array();
  for (const OpacityPoint& p : tf.opacity) j["opacity"].push_back({p.value, p.alpha});
  j["color"] = nlohmann::ordered_json::array();
  for (const ColorPoint& c : tf.color)
    j["color"].push_back({c.value, c.rgb[0], c.rgb[1], c.rgb[2]});
  return j.dump(2);
}

Status saveTransferFunction(const TransferFunction& tf, const std::string& path) {
  // A unique O_EXCL temporary, not a fixed name a symlink could be planted at.
  VOXLINK_ASSIGN_OR_RETURN(TempFile temp, createTempBeside(path, ".json"));
  const std::string text = transferFunctionJson(tf) + "\n";
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(temp.fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<size_t>(n);
  }
  const bool closed = ::close(temp.fd) == 0;
  if (done != text.size() || !closed) {
    discardTemp(temp.path);
    return makeError(ErrorCode::kIo, path, ": write failed: ", std::strerror(errno));
  }
  return commitTemp(temp.path, path);
}

}  // namespace voxlink::tf
