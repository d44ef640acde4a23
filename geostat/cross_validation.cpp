// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/cross_validation.h"

#include <cmath>

namespace voxlink::geostat {

Result<CrossValidation> leaveOneOut(const Kriger& kriger) {
  CrossValidation cv;
  const size_t n = kriger.sampleCount();
  cv.predicted.assign(n, NAN);
  cv.variance.assign(n, NAN);
  KrigingWorkspace ws;
  double sumErr = 0, sumSq = 0, sumStd = 0, sp = 0, so = 0, spp = 0, soo = 0, spo = 0;
  size_t withVariance = 0;
  for (size_t i = 0; i < n; ++i) {
    const Point3 p = kriger.sample(i);
    VOXLINK_ASSIGN_OR_RETURN(const Prediction pred, kriger.predict(p, ws, static_cast<int64_t>(i),
                                                                   kriger.sampleExternalDrift(i)));
    if (!pred.hasData) continue;
    const double observed = kriger.sampleValue(i);
    const double err = pred.value - observed;
    cv.predicted[i] = pred.value;
    cv.variance[i] = pred.variance;
    ++cv.evaluated;
    sumErr += err;
    sumSq += err * err;
    if (pred.variance > 0) {
      sumStd += err * err / pred.variance;
      ++withVariance;
    }
    sp += pred.value;
    so += observed;
    spp += pred.value * pred.value;
    soo += observed * observed;
    spo += pred.value * observed;
  }
  if (cv.evaluated == 0)
    return makeError(ErrorCode::kInvalidArgument,
                     "cross-validation: no sample has a neighbour in reach");
  const double m = static_cast<double>(cv.evaluated);
  cv.meanError = sumErr / m;
  cv.rmse = std::sqrt(sumSq / m);
  cv.meanStandardizedSquaredError = withVariance ? sumStd / static_cast<double>(withVariance) : NAN;
  const double cov = spo / m - (sp / m) * (so / m);
  const double vp = spp / m - (sp / m) * (sp / m), vo = soo / m - (so / m) * (so / m);
  cv.correlation = vp > 0 && vo > 0 ? cov / std::sqrt(vp * vo) : NAN;
  return cv;
}

}  // namespace voxlink::geostat
