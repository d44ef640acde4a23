// SPDX-License-Identifier: BSD-3-Clause
// voxlink_cholesky_bench [SYSTEMS]: the per-location kriging solve (geostat/cholesky.cpp:
// factor, 1-norm condition estimate, solve) against LAPACK's dpotrf + dpocon + dpotrs on the
// same kriging matrices (exponential covariance of random 3-D neighbourhoods), for 8..64
// neighbours. Prints ns per system (median of 5 rounds, the two alternating) and how many
// solutions agree bit for bit.
#include <cblas.h>
#include <lapacke.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "geostat/cholesky.h"

namespace {

using voxlink::geostat::Cholesky;

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct System {
  std::vector<double> a, b;  // row-major n x n, right-hand side
};

System makeSystem(size_t n, std::mt19937& random) {
  std::uniform_real_distribution<double> u(0, 10);
  std::vector<double> x(n), y(n), z(n);
  for (size_t i = 0; i < n; ++i) x[i] = u(random), y[i] = u(random), z[i] = u(random);
  System s{std::vector<double>(n * n), std::vector<double>(n)};
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < n; ++j) {
      const double d = std::hypot(x[i] - x[j], y[i] - y[j], z[i] - z[j]);
      s.a[i * n + j] = std::exp(-3 * d / 8) + (i == j ? 0.05 : 0.0);  // range 8, nugget 0.05
    }
    s.b[i] = std::exp(-3 * std::hypot(x[i] - 5, y[i] - 5, z[i] - 5) / 8);
  }
  return s;
}

double ours(const std::vector<System>& systems, size_t n, std::vector<double>& out) {
  Cholesky factor;
  double conditionSum = 0;
  for (size_t s = 0; s < systems.size(); ++s) {
    if (!factor.factor(systems[s].a, n, 0)) std::abort();
    conditionSum += factor.conditionEstimate();
    std::memcpy(&out[s * n], systems[s].b.data(), n * sizeof(double));
    factor.solve(&out[s * n]);
  }
  return conditionSum;
}

double lapack(const std::vector<System>& systems, size_t n, std::vector<double>& out) {
  std::vector<double> l(n * n);
  const int ni = static_cast<int>(n);
  double conditionSum = 0;
  for (size_t s = 0; s < systems.size(); ++s) {
    const std::vector<double>& a = systems[s].a;
    double norm1 = 0;
    for (size_t j = 0; j < n; ++j) {
      double col = 0;
      for (size_t i = 0; i < n; ++i) col += std::fabs(a[i * n + j]);
      norm1 = std::max(norm1, col);
    }
    // Row-major lower is column-major upper: LAPACKE need not transpose.
    std::memcpy(l.data(), a.data(), n * n * sizeof(double));
    if (LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'U', ni, l.data(), ni) != 0) std::abort();
    double rcond = 0;
    if (LAPACKE_dpocon(LAPACK_COL_MAJOR, 'U', ni, l.data(), ni, norm1, &rcond) != 0) std::abort();
    conditionSum += 1 / rcond;
    std::memcpy(&out[s * n], systems[s].b.data(), n * sizeof(double));
    LAPACKE_dpotrs(LAPACK_COL_MAJOR, 'U', ni, 1, l.data(), ni, &out[s * n], ni);
  }
  return conditionSum;
}

}  // namespace

int main(int argc, char** argv) {
  const size_t count = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 20000;
  openblas_set_num_threads(1);
  std::printf("%8s %14s %14s %8s %16s\n", "n", "ours ns", "LAPACK ns", "ratio", "identical bits");
  for (size_t n : {8, 16, 32, 64}) {
    std::mt19937 random(static_cast<unsigned>(n));
    std::vector<System> systems;
    for (size_t s = 0; s < count; ++s) systems.push_back(makeSystem(n, random));
    std::vector<double> x(count * n), y(count * n), tOurs, tLapack;
    double sink = 0;
    for (int round = 0; round < 5; ++round) {
      double t0 = now();
      sink += ours(systems, n, x);
      tOurs.push_back(now() - t0);
      t0 = now();
      sink += lapack(systems, n, y);
      tLapack.push_back(now() - t0);
    }
    std::sort(tOurs.begin(), tOurs.end());
    std::sort(tLapack.begin(), tLapack.end());
    size_t same = 0;
    for (size_t i = 0; i < x.size(); ++i) same += std::memcmp(&x[i], &y[i], sizeof(double)) == 0;
    const double perOurs = tOurs[2] / double(count) * 1e9,
                 perLapack = tLapack[2] / double(count) * 1e9;
    std::printf("%8zu %14.0f %14.0f %8.2f %9zu of %zu%s\n", n, perOurs, perLapack,
                perLapack / perOurs, same, x.size(), sink > 0 ? "" : " ");
  }
  return 0;
}
