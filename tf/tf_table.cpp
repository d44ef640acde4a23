// SPDX-License-Identifier: BSD-3-Clause
#include "tf/tf_table.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "format/half.h"

namespace voxlink::tf {
namespace {

// The piecewise function just below v: at a step (a value given twice) the first point holds.
template <class Point, class At>
auto leftLimit(const std::vector<Point>& points, double v, At at) {
  auto it = std::lower_bound(points.begin(), points.end(), v,
                             [](const Point& p, double x) { return p.value < x; });
  if (it != points.end() && it->value == v) return at(it->value, &*it);
  return at(v, nullptr);
}

std::array<double, 4> rgbaAt(const tf::TransferFunction& tf, double v) {
  const auto c = tf.colorAt(v);
  return {c[0], c[1], c[2], tf.opacityAt(v)};
}

std::array<double, 4> rgbaLeft(const tf::TransferFunction& tf, double v) {
  const auto color = leftLimit(
      tf.color, v, [&](double x, const tf::ColorPoint* p) { return p ? p->rgb : tf.colorAt(x); });
  const double alpha = leftLimit(tf.opacity, v, [&](double x, const tf::OpacityPoint* p) {
    return p ? p->alpha : tf.opacityAt(x);
  });
  return {color[0], color[1], color[2], alpha};
}

void push(std::vector<float>& out, const std::array<double, 4>& v) {
  for (double x : v) out.push_back(static_cast<float>(x));
}

}  // namespace

TfTable buildTfTable(const tf::TransferFunction& tf, StoredType type, double scale, double offset) {
  TfTable t;
  if (type == StoredType::kF32) {
    t.kind = TfTable::Kind::kBreakpoints;
    std::set<double> values;
    for (const auto& p : tf.opacity) values.insert(p.value);
    for (const auto& p : tf.color) values.insert(p.value);
    for (double u : values) {
      push(t.texels, {u, 0, 0, 0});
      push(t.texels, rgbaLeft(tf, u));
      push(t.texels, rgbaAt(tf, u));
    }
    t.entries = static_cast<uint32_t>(values.size());
    return t;
  }
  t.kind = TfTable::Kind::kIndexed;
  t.entries = type == StoredType::kU8 ? 256u : 65536u;
  t.texels.reserve(size_t{t.entries} * 4);
  for (uint32_t i = 0; i < t.entries; ++i) {
    const double stored =
        type == StoredType::kF16 ? double(format::halfToFloat(uint16_t(i))) : double(i);
    const double v = stored * scale + offset;
    push(t.texels, std::isfinite(v) ? rgbaAt(tf, v) : std::array<double, 4>{0, 0, 0, 0});
  }
  return t;
}

std::array<double, 4> evaluateBreakpoints(const TfTable& table, double value) {
  auto texel = [&](size_t i) {
    return std::array<double, 4>{table.texels[i * 4], table.texels[i * 4 + 1],
                                 table.texels[i * 4 + 2], table.texels[i * 4 + 3]};
  };
  const uint32_t n = table.entries;
  if (n == 0) return {0, 0, 0, 0};
  if (value < texel(0)[0]) return texel(1);
  // Largest j with u_j <= value.
  uint32_t lo = 0, hi = n - 1;
  while (lo < hi) {
    const uint32_t mid = (lo + hi + 1) / 2;
    if (texel(3 * mid)[0] <= value)
      lo = mid;
    else
      hi = mid - 1;
  }
  if (lo == n - 1) return texel(3 * lo + 2);
  const double u0 = texel(3 * lo)[0], u1 = texel(3 * (lo + 1))[0];
  const double f = (value - u0) / (u1 - u0);
  const auto a = texel(3 * lo + 2), b = texel(3 * (lo + 1) + 1);
  std::array<double, 4> r{};
  for (int c = 0; c < 4; ++c) r[c] = a[c] + (b[c] - a[c]) * f;
  return r;
}

}  // namespace voxlink::tf
