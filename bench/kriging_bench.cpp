// SPDX-License-Identifier: BSD-3-Clause
// voxlink_kriging_bench [DATA_DIR [--blas-only|--kriging-only]]: speed against error for
// kriging and random fields, after the BLAS rates global kriging can reach.
//  1. Walker Lake (470 samples -> 260 x 300 grid): neighbourhood size against time, deviation
//     from global kriging, and error against the exhaustive truth.
//  2. Scaling: 10^4 and 10^5 samples of a random field kriged onto a 512 x 512 grid.
//  3. Random fields of 256^3 and 512^3 voxels: time, throughput, peak memory, against the
//     white noise alone (the floor every voxel pays).
#include <cblas.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "geostat/grf.h"
#include "geostat/krige_grid.h"
#include "geostat/variogram_fit.h"

using namespace voxlink;
using namespace voxlink::geostat;

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double peakRssMiB() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return NAN;
}

void resetPeakRss() { std::ofstream("/proc/self/clear_refs") << "5"; }

template <class T>
T orDie(Result<T> r) {
  if (!r) {
    std::fprintf(stderr, "voxlink_kriging_bench: %s\n", r.message().c_str());
    std::exit(1);
  }
  return std::move(r).value();
}

// The worst condition estimate, or "<=B" when only the nugget's bound B is known.
std::string condition(const KrigingSummary& s) {
  char text[32];
  if (s.worstCondition >= s.worstConditionBound)
    std::snprintf(text, sizeof text, "%.3g", s.worstCondition);
  else
    std::snprintf(text, sizeof text, "<=%.3g", s.worstConditionBound);
  return text;
}

std::vector<double> krigeToVector(const Kriger& k, const GridSpec& grid, KrigingSummary& summary) {
  std::vector<double> out;
  out.reserve(grid.nodeCount());
  summary = orDie(
      krigeGrid(k, grid, [&](uint32_t, uint32_t count, const double* v, const double*) -> Status {
        out.insert(out.end(), v, v + count * grid.sliceNodes());
        return Status::ok();
      }));
  return out;
}

// What global kriging's blocks can reach on this machine: OpenBLAS's DGEMM rate, and its
// triangular solve (dtrsm) and multiply (dtrmm) on global kriging's shape (470 samples, blocks
// of 256 nodes), one thread each, as global_kriging.cpp calls them.
void blasRates() {
  const int saved = openblas_get_num_threads();
  std::printf("OpenBLAS (%s), GFlop/s\n", openblas_get_config());
  for (int threads : {1, saved}) {
    openblas_set_num_threads(threads);
    const int n = 1500;
    std::vector<double> a(size_t(n) * n, 1.0 / n), b(size_t(n) * n, 0.5), c(size_t(n) * n);
    double t0 = now();
    for (int r = 0; r < 3; ++r)
      cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, n, n, 1, a.data(), n, b.data(), n,
                  0, c.data(), n);
    std::printf("  dgemm %d^3, %d thread(s): %.1f\n", n, threads,
                3 * 2.0 * n * n * n / (now() - t0) / 1e9);
  }
  openblas_set_num_threads(1);
  const int m = 470, block = 256, repeats = 100;
  std::vector<double> l(size_t(m) * m, 0.0), k(size_t(m) * block, 1.0);
  for (int j = 0; j < m; ++j)
    for (int i = j; i < m; ++i) l[size_t(j) * m + i] = i == j ? 2.0 : 1.0 / m;
  double t0 = now();
  for (int r = 0; r < repeats; ++r)
    cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, m, block, 1.0,
                l.data(), m, k.data(), m);
  const double trsm = now() - t0;
  t0 = now();
  for (int r = 0; r < repeats; ++r)
    cblas_dtrmm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, m, block, 0.5,
                l.data(), m, k.data(), m);
  const double trmm = now() - t0;
  const double flops = double(repeats) * m * m * block;  // n^2 per right-hand side
  std::printf("  dtrsm %dx%d, 1 thread: %.1f\n  dtrmm %dx%d, 1 thread: %.1f\n\n", m, block,
              flops / trsm / 1e9, m, block, flops / trmm / 1e9);
  openblas_set_num_threads(saved);
}

void walkerLake(const std::string& dataDir) {
  const std::string samplesPath = dataDir + "/geostat/gstat_csv/walker.csv";
  auto samples = readPoints(samplesPath, {"X", "Y", "", "V"});
  auto truthPoints = readPoints(dataDir + "/geostat/gstat_csv/walker.exh.csv", {"x", "y", "", "V"});
  if (!samples || !truthPoints) {
    std::printf("Walker Lake data missing under %s: skipped\n\n", dataDir.c_str());
    return;
  }
  std::vector<double> truth(78000);
  for (size_t i = 0; i < truthPoints->size(); ++i)
    truth[size_t(truthPoints->coords[i][1] - 1) * 260 + size_t(truthPoints->coords[i][0] - 1)] =
        truthPoints->values[i];
  const auto bins = orDie(experimentalVariogram(*samples));
  const Variogram v =
      orDie(Variogram::make(orDie(fitVariogram(bins, {VariogramType::kSpherical}))));
  const GridSpec grid{{260, 300, 1}, {1, 1, 0}, {1, 1, 1}};
  double sd = 0, mean = 0;
  for (double s : samples->values) mean += s / double(samples->size());
  for (double s : samples->values) sd += (s - mean) * (s - mean) / double(samples->size());
  sd = std::sqrt(sd);
  std::printf("Walker Lake: %zu samples of V -> 260 x 300 grid, %s, 2 threads\n", samples->size(),
              v.describe().c_str());
  std::printf("%6s %9s %8s %13s %13s %10s %10s %10s\n", "k", "time_s", "vs_all", "max|d|/sd",
              "rms|d|/sd", "RMSE", "ME", "worst_cond");
  KrigingSummary globalSummary;
  const Kriger global = orDie(Kriger::make(*samples, v, {}));
  double t0 = now();
  const std::vector<double> reference = krigeToVector(global, grid, globalSummary);
  const double globalTime = now() - t0;
  for (size_t k : {size_t{8}, size_t{16}, size_t{32}, size_t{64}, size_t{128}, size_t{0}}) {
    const Kriger local = orDie(Kriger::make(*samples, v, {.maxNeighbours = k}));
    KrigingSummary summary;
    t0 = now();
    const std::vector<double> pred = k == 0 ? reference : krigeToVector(local, grid, summary);
    const double t = k == 0 ? globalTime : now() - t0;
    if (k == 0) summary = globalSummary;
    double maxDiff = 0, sumSq = 0, err = 0, errSq = 0;
    for (size_t i = 0; i < pred.size(); ++i) {
      const double d = std::fabs(pred[i] - reference[i]);
      maxDiff = std::max(maxDiff, d);
      sumSq += d * d;
      err += pred[i] - truth[i];
      errSq += (pred[i] - truth[i]) * (pred[i] - truth[i]);
    }
    const double n = double(pred.size());
    std::printf("%6s %9.3f %8.2f %13.3e %13.3e %10.2f %10.2f %10s\n",
                k ? std::to_string(k).c_str() : "all", t, t / globalTime, maxDiff / sd,
                std::sqrt(sumSq / n) / sd, std::sqrt(errSq / n), err / n,
                condition(summary).c_str());
  }
  std::printf("\n");
}

void scaling() {
  // Samples of a 2-D random field at random places, kriged with the field's own model.
  GrfSpec field;
  field.dims = {2048, 2048, 1};
  field.model = {VariogramType::kExponential, 0, 1, 200, 0.5};
  field.seed = 5;
  std::vector<float> values;
  values.reserve(2048 * 2048);
  orDie(generateGrf(field, [&](uint32_t, uint32_t count, const double* slab) -> Status {
    values.insert(values.end(), slab, slab + count * 2048ull * 2048);
    return Status::ok();
  }));
  const Variogram v = orDie(Variogram::make(field.model));
  std::printf(
      "Scaling: samples of a 2048^2 random field (%s) kriged onto 512 x 512 nodes, 2 threads\n",
      v.describe().c_str());
  std::printf("%8s %4s %9s %12s %12s %10s\n", "samples", "k", "time_s", "nodes/s", "RMSE",
              "worst_cond");
  for (size_t n : {size_t{10000}, size_t{100000}}) {
    PointSet s;
    uint64_t state = 12345;
    auto next = [&] {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return uint32_t(state >> 33) % 2048;
    };
    for (size_t i = 0; i < n; ++i) {
      const uint32_t x = next(), y = next();
      s.coords.push_back({double(x), double(y), 0});
      s.values.push_back(values[size_t(y) * 2048 + x]);
    }
    for (size_t k : {size_t{16}, size_t{32}}) {
      const Kriger kr = orDie(Kriger::make(s, v, {.maxNeighbours = k}));
      const GridSpec grid{{512, 512, 1}, {1.5, 1.5, 0}, {4, 4, 1}};
      KrigingSummary summary;
      const double t0 = now();
      const std::vector<double> pred = krigeToVector(kr, grid, summary);
      const double t = now() - t0;
      double errSq = 0;
      for (uint32_t j = 0; j < 512; ++j)
        for (uint32_t i = 0; i < 512; ++i) {
          // Nodes fall between lattice points: compare with the nearest lattice value.
          const double truth =
              values[size_t(std::lround(1.5 + 4 * j)) * 2048 + size_t(std::lround(1.5 + 4 * i))];
          errSq += (pred[j * 512 + i] - truth) * (pred[j * 512 + i] - truth);
        }
      std::printf("%8zu %4zu %9.3f %12.0f %12.4f %10s\n", n, k, t, 512.0 * 512 / t,
                  std::sqrt(errSq / (512.0 * 512)), condition(summary).c_str());
    }
  }
  std::printf("\n");
}

void randomFields() {
  std::printf(
      "Random fields, exponential practical range 32 voxels, sill 1, 2 threads, output "
      "discarded\n");
  std::printf("%6s %9s %9s %12s %10s %10s %10s %9s\n", "size", "noise_s", "field_s", "Mvoxels/s",
              "vs_noise", "peak_MiB", "out_MiB", "kernel_r");
  for (uint32_t n : {256u, 512u}) {
    // Floor: the hashed white noise for every output voxel, nothing else.
    double t0 = now();
    double sink = 0;
    for (uint32_t z = 0; z < n; ++z)
      for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x) sink += latticeNoise(1, x, y, z);
    const double noise = now() - t0;
    GrfSpec spec;
    spec.dims = {n, n, n};
    spec.model = {VariogramType::kExponential, 0, 1, 32, 0.5};
    resetPeakRss();
    const double before = peakRssMiB();
    t0 = now();
    const GrfReport r =
        orDie(generateGrf(spec, [&](uint32_t, uint32_t, const double* slab) -> Status {
          sink += slab[0];
          return Status::ok();
        }));
    const double t = now() - t0;
    const double voxels = double(n) * n * n;
    std::printf(
        "%6u %9.2f %9.2f %12.1f %10.2f %10.0f %10.0f %9u   (checksum %.3g, RSS before %.0f MiB)\n",
        n, noise, t, voxels / t / 1e6, t / noise, peakRssMiB(), voxels * 8 / (1 << 20),
        r.kernel.radius, sink, before);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dataDir = argc > 1 ? argv[1] : VOXLINK_BENCH_DATA_DIR;
  const std::string only = argc > 2 ? argv[2] : "";
  blasRates();
  if (only == "--blas-only") return 0;
  walkerLake(dataDir);
  scaling();
  if (only == "--kriging-only") return 0;
  randomFields();
  return 0;
}
