// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/grf.h"

#include <fftw3.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <sstream>

#include "base/parallel_for.h"
#include "base/process_memory.h"

namespace voxlink::geostat {
namespace {

constexpr int64_t kCoordinateBias = int64_t{1} << 20;
std::mutex planMutex;  // FFTW's planner is not thread-safe

uint64_t mix64(uint64_t z) {  // splitmix64 finalizer
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

bool isFftFriendly(uint32_t n) {
  for (uint32_t p : {2u, 3u, 5u, 7u})
    while (n % p == 0) n /= p;
  return n == 1;
}

uint32_t fftFriendlyAtLeast(uint32_t n) {
  while (!isFftFriendly(n)) ++n;
  return n;
}

struct FftwDeleter {
  void operator()(void* p) const { fftw_free(p); }
};

// The FFT size along one axis: the cheapest total work (blocks x size) for the grid, with
// the size at most maxSize.
uint32_t chooseFftSize(uint32_t n, uint32_t radius, uint32_t maxSize) {
  uint32_t best = fftFriendlyAtLeast(n + 2 * radius);
  double bestCost = INFINITY;
  for (uint32_t blocks = 1; blocks <= n; ++blocks) {
    const uint32_t b = (n + blocks - 1) / blocks;
    const uint32_t p = fftFriendlyAtLeast(b + 2 * radius);
    if (p > maxSize) continue;
    const double cost = double(blocks) * p * std::log2(double(p) + 1);
    if (cost < bestCost) {
      bestCost = cost;
      best = p;
    }
    if (b <= radius / 4 + 1) break;  // blocks much thinner than the kernel only waste work
  }
  return best;
}

}  // namespace

// Box-Muller on one hashed pair of uniforms per two neighbouring x: the even x takes the
// cosine, the odd x the sine (independent standard normals), halving log/sqrt/sincos work.
void latticeNoisePair(uint64_t seed, int64_t xPair, int64_t y, int64_t z, double& even,
                      double& odd) {
  const uint64_t key = (uint64_t(xPair + kCoordinateBias) << 42) ^
                       (uint64_t(y + kCoordinateBias) << 21) ^ uint64_t(z + kCoordinateBias);
  const uint64_t h1 = mix64(key + mix64(seed + 0x9e3779b97f4a7c15ULL));
  const uint64_t h2 = mix64(h1 ^ 0xd1b54a32d192ed03ULL);
  const double u1 = (double((h1 >> 11) + 1)) * 0x1.0p-53;  // (0, 1]
  const double u2 = double(h2 >> 11) * 0x1.0p-53;
  const double radius = std::sqrt(-2.0 * std::log(u1));
  even = radius * std::cos(2.0 * M_PI * u2);
  odd = radius * std::sin(2.0 * M_PI * u2);
}

double latticeNoise(uint64_t seed, int64_t x, int64_t y, int64_t z) {
  double even, odd;
  latticeNoisePair(seed, x >> 1, y, z, even, odd);  // arithmetic shift: floor(x / 2)
  return (x & 1) ? odd : even;
}

std::string GrfReport::text() const {
  std::ostringstream out;
  out.precision(3);
  out << "kernel: radius " << kernel.radius << " voxels, embedding half-period "
      << kernel.embeddingHalfSize << ", C(H)/sill " << kernel.covarianceAtHalfSize
      << ", clipped negative eigenvalues " << kernel.negativeEigenvalueMass
      << ", truncated kernel energy " << kernel.truncatedEnergy << "\n"
      << "blocks: " << blocks << " of " << blockSize[0] << "x" << blockSize[1] << "x"
      << blockSize[2] << " voxels, FFT " << fftSize[0] << "x" << fftSize[1] << "x" << fftSize[2]
      << ", " << threads << (threads == 1 ? " thread" : " threads") << "\n"
      << "buffers: " << double(peakBufferBytes) / (1 << 20) << " MiB peak besides the sink\n"
      << "time: " << kernelSeconds << " s kernel, " << seconds << " s total\n";
  return out.str();
}

Result<GrfReport> generateGrf(const GrfSpec& spec, const GrfSink& sink) {
  const uint64_t sliceVoxels = uint64_t{spec.dims[0]} * spec.dims[1];
  return generateGrfPart(spec, GridPart{},
                         [&](uint64_t first, uint64_t voxels, const double* slab, const double*) {
                           return sink(static_cast<uint32_t>(first / sliceVoxels),
                                       static_cast<uint32_t>(voxels / sliceVoxels), slab);
                         });
}

Result<GrfReport> generateGrfPart(const GrfSpec& spec, const GridPart& part,
                                  const NodeRunSink& sink) {
  if (part.count == 0 || part.index >= part.count)
    return makeError(ErrorCode::kInvalidArgument, "random field: share ", part.index, " of ",
                     part.count);
  VOXLINK_RETURN_IF_ERROR(base::checkThreadCount(spec.threads, "random field: threads"));
  for (int a = 0; a < 3; ++a)
    if (spec.dims[a] == 0 || spec.dims[a] > kMaxGrfAxis)
      return makeError(ErrorCode::kInvalidArgument, "random field: dims axis ", a,
                       " must be in 1..", kMaxGrfAxis, ", got ", spec.dims[a]);
  VOXLINK_ASSIGN_OR_RETURN(const Variogram variogram, Variogram::make(spec.model));
  const auto start = std::chrono::steady_clock::now();
  GrfReport report;
  const std::array<bool, 3> active{spec.dims[0] > 1, spec.dims[1] > 1, spec.dims[2] > 1};
  VOXLINK_ASSIGN_OR_RETURN(report.kernel, makeGrfKernel(variogram, active, spec.kernel));
  report.kernelSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const GrfKernel& kernel = report.kernel;
  const uint32_t R = kernel.radius;
  const int dimension = int{active[0]} + int{active[1]} + int{active[2]};
  // In-place transforms: one complex array of P^3 / 2 values, 8 bytes per real point.
  const double maxPoints = double(spec.maxBlockBytes) / sizeof(double);
  const uint32_t maxSize = static_cast<uint32_t>(std::pow(maxPoints, 1.0 / dimension));
  std::array<uint32_t, 3> P{1, 1, 1}, B{1, 1, 1}, r{0, 0, 0};
  for (int a = 0; a < 3; ++a) {
    if (!active[a]) continue;
    r[a] = R;
    P[a] = spec.fftSize
               ? fftFriendlyAtLeast(std::max(spec.fftSize, 2 * R + 1))
               : chooseFftSize(spec.dims[a], R, std::max(maxSize, fftFriendlyAtLeast(2 * R + 2)));
    B[a] = std::min(P[a] - 2 * R, spec.dims[a]);
  }
  report.fftSize = P;
  report.blockSize = B;
  const uint64_t realCount = uint64_t{P[0]} * P[1] * P[2];
  const uint32_t rowStride = 2 * (P[0] / 2 + 1);  // padded real rows of an in-place r2c
  const uint64_t complexCount = uint64_t{P[0] / 2 + 1} * P[1] * P[2];
  const std::array<uint32_t, 3> nb{(spec.dims[0] + B[0] - 1) / B[0],
                                   (spec.dims[1] + B[1] - 1) / B[1],
                                   (spec.dims[2] + B[2] - 1) / B[2]};
  unsigned threads =
      std::max(1u, std::min<unsigned>(base::threadCount(spec.threads), nb[0] * nb[1]));
  // The units of a share: rows of blocks (along y), z block by z block; its slab holds the
  // share's rows only.
  const uint64_t firstRow = part.firstUnit(uint64_t{nb[2]} * nb[1]);
  const uint64_t endRow = part.endUnit(uint64_t{nb[2]} * nb[1]);
  const uint64_t slabRows = std::min<uint64_t>(spec.dims[1], (endRow - firstRow) * B[1]);
  const uint64_t slabBytes = uint64_t{spec.dims[0]} * slabRows * B[2] * sizeof(double);
  const uint64_t blockBytes = complexCount * sizeof(fftw_complex);
  // The FFT block must hold the kernel's reach on both sides, so a long range needs large
  // blocks. Fewer threads than asked for when their blocks do not all fit; none fitting is
  // refused now rather than by the OOM killer once the pages are touched.
  const double memory = double(spec.memoryBytes ? spec.memoryBytes : base::memoryForThisProcess());
  if (double(slabBytes) > memory)
    return makeError(ErrorCode::kTooLarge, "random field: an output slab of ", spec.dims[0], " x ",
                     slabRows, " x ", B[2], " voxels (", std::round(double(slabBytes) / 1e8) / 10,
                     " GB) does not fit in the ", std::round(memory / 1e8) / 10,
                     " GB this process may use");
  const double kernelBytes = double(kernel.octant.size()) * sizeof(double);
  const double fixedBytes = double(slabBytes) + double(complexCount) * sizeof(double) + kernelBytes;
  if (fixedBytes + double(blockBytes) > memory)
    return makeError(ErrorCode::kTooLarge, "random field: range ", spec.model.range,
                     " voxels needs FFT blocks of ", P[0], " x ", P[1], " x ", P[2], " (",
                     std::round(double(blockBytes) / 1e8) / 10, " GB each, ",
                     std::round((fixedBytes + double(blockBytes)) / 1e8) / 10,
                     " GB with one thread); this process may use ", std::round(memory / 1e8) / 10,
                     " GB (a shorter range, or a coarser grid with the range in its voxels)");
  while (threads > 1 && fixedBytes + double(threads) * double(blockBytes) > memory) --threads;
  report.threads = threads;
  report.peakBufferBytes = std::max(
      kernel.embeddingBytes, threads * blockBytes + slabBytes + complexCount * sizeof(double));

  auto allocate = [&]() { return static_cast<fftw_complex*>(fftw_malloc(blockBytes)); };
  std::unique_ptr<double, FftwDeleter> spectrum(
      static_cast<double*>(fftw_malloc(complexCount * sizeof(double))));
  std::vector<std::unique_ptr<fftw_complex, FftwDeleter>> buffers(threads);
  for (auto& b : buffers) b.reset(allocate());
  std::vector<double> slab;
  try {
    slab.resize(slabBytes / sizeof(double));
  } catch (const std::bad_alloc&) {
    return makeError(ErrorCode::kTooLarge, "random field: an output slab of ", slabBytes,
                     " bytes does not fit in memory");
  }
  for (const auto& b : buffers)
    if (!b || !spectrum)
      return makeError(ErrorCode::kTooLarge, "random field: cannot allocate FFT buffers of ",
                       blockBytes, " bytes per thread");
  fftw_plan forward, backward;
  {
    std::lock_guard lock(planMutex);
    double* real = reinterpret_cast<double*>(buffers[0].get());
    forward = fftw_plan_dft_r2c_3d(int(P[2]), int(P[1]), int(P[0]), real, buffers[0].get(),
                                   FFTW_ESTIMATE);
    backward = fftw_plan_dft_c2r_3d(int(P[2]), int(P[1]), int(P[0]), buffers[0].get(), real,
                                    FFTW_ESTIMATE);
  }
  auto realAt = [&](double* real, uint64_t x, uint64_t y, uint64_t z) -> double& {
    return real[(z * P[1] + y) * rowStride + x];
  };
  // Kernel spectrum: the truncated kernel wrapped into the periodic block, transformed. The
  // kernel is real and even, so its spectrum is real.
  {
    double* real = reinterpret_cast<double*>(buffers[0].get());
    std::fill(real, real + 2 * complexCount, 0.0);
    for (int64_t dz = -int64_t(r[2]); dz <= int64_t(r[2]); ++dz)
      for (int64_t dy = -int64_t(r[1]); dy <= int64_t(r[1]); ++dy)
        for (int64_t dx = -int64_t(r[0]); dx <= int64_t(r[0]); ++dx)
          realAt(real, uint64_t((dx + P[0]) % P[0]), uint64_t((dy + P[1]) % P[1]),
                 uint64_t((dz + P[2]) % P[2])) =
              kernel.at(uint32_t(std::abs(dx)), uint32_t(std::abs(dy)), uint32_t(std::abs(dz)));
    fftw_execute_dft_r2c(forward, real, buffers[0].get());
    for (uint64_t i = 0; i < complexCount; ++i)
      spectrum.get()[i] = buffers[0].get()[i][0] / double(realCount);
  }

  report.blocks = (endRow - firstRow) * nb[0];
  Status status;
  for (uint64_t bz = firstRow / nb[1]; status && firstRow < endRow && bz * nb[1] < endRow; ++bz) {
    const uint32_t z0 = static_cast<uint32_t>(bz) * B[2];
    const uint32_t zCount = std::min(B[2], spec.dims[2] - z0);
    const uint32_t rowBegin = static_cast<uint32_t>(std::max(firstRow, bz * nb[1]) - bz * nb[1]);
    const uint32_t rowEnd = static_cast<uint32_t>(std::min(endRow, (bz + 1) * nb[1]) - bz * nb[1]);
    const uint32_t yBase = rowBegin * B[1], rows = std::min(rowEnd * B[1], spec.dims[1]) - yBase;
    std::atomic<uint32_t> next{rowBegin * nb[0]};
    auto work = [&](unsigned t) {
      fftw_complex* freq = buffers[t].get();
      double* real = reinterpret_cast<double*>(freq);
      for (uint32_t job = next++; job < rowEnd * nb[0]; job = next++) {
        const uint32_t x0 = (job % nb[0]) * B[0], y0 = (job / nb[0]) * B[1];
        // Noise for the block plus the kernel's reach on every side; pairs start at even x.
        const int64_t gx0 = int64_t(x0) - r[0];
        for (uint32_t k = 0; k < P[2]; ++k)
          for (uint32_t j = 0; j < P[1]; ++j) {
            double* row = &realAt(real, 0, j, k);
            const int64_t gz = int64_t(z0) + k - r[2], gy = int64_t(y0) + j - r[1];
            uint32_t i = 0;
            if (gx0 & 1) row[i++] = latticeNoise(spec.seed, gx0, gy, gz);
            for (; i + 1 < P[0]; i += 2)
              latticeNoisePair(spec.seed, (gx0 + i) >> 1, gy, gz, row[i], row[i + 1]);
            if (i < P[0]) row[i] = latticeNoise(spec.seed, gx0 + i, gy, gz);
          }
        fftw_execute_dft_r2c(forward, real, freq);
        const double* s = spectrum.get();
        for (uint64_t i = 0; i < complexCount; ++i) {
          freq[i][0] *= s[i];
          freq[i][1] *= s[i];
        }
        fftw_execute_dft_c2r(backward, freq, real);
        const uint32_t xCount = std::min(B[0], spec.dims[0] - x0),
                       yCount = std::min(B[1], spec.dims[1] - y0);
        for (uint32_t k = 0; k < zCount; ++k)
          for (uint32_t j = 0; j < yCount; ++j) {
            const double* src = &realAt(real, r[0], j + r[1], k + r[2]);
            double* dst = slab.data() + (uint64_t{k} * rows + y0 + j - yBase) * spec.dims[0] + x0;
            for (uint32_t i = 0; i < xCount; ++i) dst[i] = src[i] + spec.mean;
          }
      }
    };
    base::runOnThreads(threads, work);
    status = forEachRowRun(spec.dims, z0, zCount, yBase, yBase + rows,
                           [&](uint64_t first, uint64_t voxels, uint64_t offset) {
                             return sink(first, voxels, slab.data() + offset, nullptr);
                           });
  }
  fftw_destroy_plan(forward);
  fftw_destroy_plan(backward);
  if (!status) return status.error();
  report.kernel.octant.clear();
  report.kernel.octant.shrink_to_fit();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace voxlink::geostat
