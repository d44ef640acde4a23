// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/variogram.h"

#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "geostat/detail/exp_batch.h"

namespace voxlink::geostat {
namespace {

// exp(-3) ~ 0.0498: the factor 3 of the usual exponential and Gaussian practical ranges.
const double kPracticalCorrelation = std::exp(-3.0);

// Spherical covariances of n distances (h, or h squared), operation by operation as
// correlation() and covariance(), so the same bits. The AVX2 clone does four distances per
// vector: the square roots and divides bound the loop, and a 256-bit divide costs about what a
// 128-bit one does. "avx2" without "fma" (or avx512f, which implies it), so no multiply-add
// is fused and no bit changes.
__attribute__((target_clones("avx2", "default"))) void sphericalOfSquared(
    const double* __restrict squared, double* __restrict out, size_t n, double a, double psill,
    double total) {
  for (size_t i = 0; i < n; ++i) {
    const double h = std::sqrt(squared[i]), t = h / a;
    const double c = h >= a ? 0.0 : 1.0 - 1.5 * t + 0.5 * t * t * t;
    out[i] = h == 0.0 ? total : psill * c;
  }
}

__attribute__((target_clones("avx2", "default"))) void sphericalOfDistance(
    const double* __restrict distance, double* __restrict out, size_t n, double a, double psill,
    double total) {
  for (size_t i = 0; i < n; ++i) {
    const double h = distance[i], t = h / a;
    const double c = h >= a ? 0.0 : 1.0 - 1.5 * t + 0.5 * t * t * t;
    out[i] = h == 0.0 ? total : psill * c;
  }
}

double maternCorrelation(double h, double scale, double nu, double norm) {
  const double x = h / scale;
  if (x < 1e-12) return 1.0;
  if (x > 700.0) return 0.0;  // K_nu underflows long before; avoids inf * 0
  return norm * std::pow(x, nu) * std::cyl_bessel_k(nu, x);
}

}  // namespace

const char* variogramTypeName(VariogramType type) {
  switch (type) {
    case VariogramType::kExponential:
      return "exponential";
    case VariogramType::kSpherical:
      return "spherical";
    case VariogramType::kGaussian:
      return "gaussian";
    case VariogramType::kMatern:
      return "matern";
  }
  return "?";
}

Result<Variogram> Variogram::make(const VariogramParams& p) {
  const char* name = variogramTypeName(p.type);
  if (!std::isfinite(p.nugget) || p.nugget < 0)
    return makeError(ErrorCode::kInvalidArgument, "variogram ", name,
                     ": nugget must be finite and >= 0, got ", p.nugget);
  if (!std::isfinite(p.psill) || p.psill < 0)
    return makeError(ErrorCode::kInvalidArgument, "variogram ", name,
                     ": psill must be finite and >= 0, got ", p.psill);
  if (!(p.nugget + p.psill > 0))
    return makeError(ErrorCode::kInvalidArgument, "variogram ", name,
                     ": sill (nugget + psill) must be > 0");
  if (!std::isfinite(p.range) || p.range <= 0)
    return makeError(ErrorCode::kInvalidArgument, "variogram ", name,
                     ": range must be finite and > 0, got ", p.range);
  Variogram v;
  v.params_ = p;
  if (p.type == VariogramType::kMatern) {
    if (!std::isfinite(p.smoothness) || p.smoothness < 0.05 || p.smoothness > 50)
      return makeError(ErrorCode::kInvalidArgument,
                       "variogram matern: smoothness nu must be in [0.05, 50], got ", p.smoothness);
    const double nu = p.smoothness;
    v.maternNorm_ = std::exp((1.0 - nu) * std::log(2.0) - std::lgamma(nu));
    // rho(range; scale) decreases as range/scale grows: bisect x = range/scale in log space.
    double lo = 1e-6, hi = 1e3;
    for (int i = 0; i < 200; ++i) {
      const double mid = std::sqrt(lo * hi);
      if (maternCorrelation(mid, 1.0, nu, v.maternNorm_) > kPracticalCorrelation)
        lo = mid;
      else
        hi = mid;
    }
    v.maternScale_ = p.range / std::sqrt(lo * hi);
  }
  return v;
}

double Variogram::correlation(double h) const {
  const double a = params_.range;
  switch (params_.type) {
    case VariogramType::kExponential:
      return std::exp(-3.0 * h / a);
    case VariogramType::kSpherical: {
      if (h >= a) return 0.0;
      const double t = h / a;
      return 1.0 - 1.5 * t + 0.5 * t * t * t;
    }
    case VariogramType::kGaussian:
      return std::exp(-3.0 * (h / a) * (h / a));
    case VariogramType::kMatern:
      return maternCorrelation(h, maternScale_, params_.smoothness, maternNorm_);
  }
  return 0.0;
}

void Variogram::covariancesOfSquared(const double* squared, double* out, size_t n) const {
  const double a = params_.range, psill = params_.psill, total = sill();
  switch (params_.type) {
    case VariogramType::kExponential:
      for (size_t i = 0; i < n; ++i) out[i] = -3.0 * std::sqrt(squared[i]) / a;
      expBatch(out, out, n);
      for (size_t i = 0; i < n; ++i) out[i] = squared[i] == 0.0 ? total : psill * out[i];
      return;
    case VariogramType::kSpherical:
      return sphericalOfSquared(squared, out, n, a, psill, total);
    case VariogramType::kGaussian:
    case VariogramType::kMatern:
      break;
  }
  for (size_t i = 0; i < n; ++i) out[i] = covariance(std::sqrt(squared[i]));
}

void Variogram::covariances(const double* h, double* out, size_t n) const {
  const double a = params_.range, psill = params_.psill, total = sill();
  if (params_.type == VariogramType::kSpherical)
    return sphericalOfDistance(h, out, n, a, psill, total);
  if (params_.type != VariogramType::kExponential) {
    for (size_t i = 0; i < n; ++i) out[i] = covariance(h[i]);
    return;
  }
  for (size_t i = 0; i < n; ++i) out[i] = -3.0 * h[i] / a;  // correlation()'s operations
  expBatch(out, out, n);
  for (size_t i = 0; i < n; ++i) out[i] = h[i] == 0.0 ? total : psill * out[i];
}

std::string Variogram::describe() const {
  std::ostringstream out;
  out.precision(6);
  out << variogramTypeName(params_.type) << "(nugget=" << params_.nugget
      << ", psill=" << params_.psill << ", range=" << params_.range;
  if (params_.type == VariogramType::kMatern)
    out << ", nu=" << params_.smoothness << ", scale=" << maternScale_;
  out << ")";
  return out.str();
}

Result<VariogramParams> parseVariogram(const std::string& text) {
  const auto colon = text.find(':');
  const std::string typeName = text.substr(0, colon);
  static const std::map<std::string, VariogramType> kTypes = {
      {"exp", VariogramType::kExponential}, {"exponential", VariogramType::kExponential},
      {"sph", VariogramType::kSpherical},   {"spherical", VariogramType::kSpherical},
      {"gau", VariogramType::kGaussian},    {"gaussian", VariogramType::kGaussian},
      {"mat", VariogramType::kMatern},      {"matern", VariogramType::kMatern}};
  const auto type = kTypes.find(typeName);
  if (type == kTypes.end())
    return makeError(ErrorCode::kInvalidArgument, "--variogram '", text, "': model '", typeName,
                     "' is not one of exp, sph, gau, mat");
  VariogramParams p;
  p.type = type->second;
  bool haveRange = false;
  std::optional<double> totalSill;
  std::stringstream rest(colon == std::string::npos ? "" : text.substr(colon + 1));
  std::string item;
  while (std::getline(rest, item, ',')) {
    const auto eq = item.find('=');
    const std::string key = item.substr(0, eq);
    const std::string valueText = eq == std::string::npos ? "" : item.substr(eq + 1);
    char* end = nullptr;
    const double value = std::strtod(valueText.c_str(), &end);
    if (valueText.empty() || *end != '\0')
      return makeError(ErrorCode::kInvalidArgument, "--variogram '", text, "': '", item,
                       "' is not key=number");
    if (key == "nugget")
      p.nugget = value;
    else if (key == "psill")
      p.psill = value;
    else if (key == "sill")
      totalSill = value;
    else if (key == "range") {
      p.range = value;
      haveRange = true;
    } else if (key == "nu" || key == "smoothness")
      p.smoothness = value;
    else
      return makeError(ErrorCode::kInvalidArgument, "--variogram '", text, "': unknown key '", key,
                       "' (nugget, psill, sill, range, nu)");
  }
  if (!haveRange)
    return makeError(ErrorCode::kInvalidArgument, "--variogram '", text,
                     "': range=... is required");
  if (totalSill) p.psill = *totalSill - p.nugget;
  VOXLINK_RETURN_IF_ERROR(Variogram::make(p).status());
  return p;
}

}  // namespace voxlink::geostat
