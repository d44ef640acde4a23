// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/spd_batch_kernels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "geostat/detail/spd_kernels.h"
#include "tests/geostat/spd_test_util.h"

namespace voxlink::geostat {
namespace {

using spd::batch::kLanes;

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every lane of the batch kernels gives the scalar kernels' bits, and a lane whose matrix is
// not positive definite fails alone.
TEST(SpdBatchKernels, EveryLaneEqualsTheScalarKernelsBitForBit) {
  std::mt19937 rng(7);
  for (size_t n : {1, 2, 3, 5, 16, 31, 32, 33, 48}) {
    for (double range : {0.1, 1.0, 4.0}) {
      const size_t ld = spd::paddedSize(n);
      std::vector<std::vector<double>> scalar(kLanes);
      std::vector<double> compact(n * n * kLanes, 0.0);
      for (size_t lane = 0; lane < kLanes; ++lane) {
        scalar[lane] = test::randomCovariances(n, range, rng);
        // Lane 3 is made indefinite (a negative last pivot) where the size allows it.
        if (lane == 3 && n > 1) scalar[lane][(n - 1) * ld + n - 1] = -1;
        for (size_t j = 0; j < n; ++j)
          for (size_t i = j; i < n; ++i)
            compact[spd::batch::at(i, j, n, lane)] = scalar[lane][j * ld + i];
      }
      uint8_t ok[kLanes];
      spd::batch::factorLower(compact.data(), n, ok);
      for (size_t lane = 0; lane < kLanes; ++lane) {
        const bool scalarOk = spd::factorLower(scalar[lane].data(), n, ld);
        ASSERT_EQ(scalarOk, ok[lane] != 0) << "n " << n << " lane " << lane;
        if (lane == 3 && n > 1) {
          EXPECT_FALSE(scalarOk);
        }
        if (!scalarOk) continue;
        for (size_t j = 0; j < n; ++j) {
          for (size_t i = j; i < n; ++i) {
            ASSERT_TRUE(sameBits(compact[spd::batch::at(i, j, n, lane)], scalar[lane][j * ld + i]))
                << "n " << n << " range " << range << " lane " << lane << " (" << i << ", " << j
                << ")";
          }
        }
      }
    }
  }
}

// unpackLower gives each of the first `count` lanes its lower triangle, column-major with the
// leading dimension asked for, and writes nothing for the other lanes.
TEST(SpdBatchKernels, UnpackLowerCopiesEachLanesLowerTriangle) {
  for (size_t n : {1, 2, 3, 4, 5, 7, 16, 31, 32, 33}) {
    const size_t ld = spd::paddedSize(n) + 4;
    std::vector<double> compact(n * n * kLanes);
    for (size_t k = 0; k < compact.size(); ++k) compact[k] = double(k) + 0.5;
    for (size_t count = 1; count <= kLanes; ++count) {
      std::vector<std::vector<double>> out(kLanes, std::vector<double>(ld * n, -1.0));
      double* factors[kLanes];
      for (size_t lane = 0; lane < kLanes; ++lane) factors[lane] = out[lane].data();
      spd::batch::unpackLower(compact.data(), n, count, factors, ld);
      for (size_t lane = 0; lane < kLanes; ++lane)
        for (size_t j = 0; j < n; ++j)
          for (size_t i = j; i < ld; ++i) {
            const double expected =
                lane < count && i < n ? compact[spd::batch::at(i, j, n, lane)] : -1.0;
            ASSERT_EQ(out[lane][j * ld + i], expected)
                << "n " << n << " count " << count << " lane " << lane << " (" << i << ", " << j
                << ")";
          }
    }
  }
}

// norm1 per lane is the column sums in local kriging's gather() order, bit for bit.
TEST(SpdBatchKernels, Norm1EqualsTheGatherOrderBitForBit) {
  std::mt19937 rng(13);
  for (size_t n : {1, 2, 3, 16, 32, 33}) {
    const size_t ld = spd::paddedSize(n);
    std::vector<double> compact(n * n * kLanes, 0.0);
    std::vector<std::vector<double>> scalar(kLanes);
    for (size_t lane = 0; lane < kLanes; ++lane) {
      scalar[lane] = test::randomCovariances(n, 0.5, rng);
      for (size_t j = 0; j < n; ++j)
        for (size_t i = j; i < n; ++i)
          compact[spd::batch::at(i, j, n, lane)] = scalar[lane][j * ld + i] * (i % 3 ? 1 : -1);
    }
    std::vector<double> work(n * kLanes);
    double norm[kLanes];
    spd::batch::norm1(compact.data(), n, work.data(), norm);
    for (size_t lane = 0; lane < kLanes; ++lane) {
      std::vector<double> sums(n, 0.0);
      for (size_t j = 0; j < n; ++j) {
        double sum = std::fabs(compact[spd::batch::at(j, j, n, lane)]);
        for (size_t i = j + 1; i < n; ++i) {
          const double v = std::fabs(compact[spd::batch::at(i, j, n, lane)]);
          sum += v;
          sums[i] += v;
        }
        sums[j] += sum;
      }
      EXPECT_TRUE(sameBits(norm[lane], *std::max_element(sums.begin(), sums.end())))
          << "n " << n << " lane " << lane;
    }
  }
}

// The comparison bound per lane equals the scalar kernel's to rounding (the same sums in the
// same order; FMA contraction may differ), and it bounds ||A^-1||_1 from above.
TEST(SpdBatchKernels, ComparisonBoundEqualsTheScalarBoundPerLane) {
  std::mt19937 rng(11);
  size_t checked = 0;
  for (size_t n : {1, 2, 3, 5, 16, 31, 32, 33, 48}) {
    for (double range : {0.1, 1.0, 4.0}) {
      const size_t ld = spd::paddedSize(n);
      std::vector<std::vector<double>> scalar(kLanes);
      std::vector<double> compact(n * n * kLanes, 0.0);
      for (size_t lane = 0; lane < kLanes; ++lane) {
        scalar[lane] = test::randomCovariances(n, range, rng);
        for (size_t j = 0; j < n; ++j)
          for (size_t i = j; i < n; ++i)
            compact[spd::batch::at(i, j, n, lane)] = scalar[lane][j * ld + i];
      }
      uint8_t ok[kLanes];
      spd::batch::factorLower(compact.data(), n, ok);
      std::vector<double> work(2 * n * kLanes + n * (n + 1));
      double bound[kLanes];
      spd::batch::inverseNormComparisonBound(compact.data(), n, work.data(), bound);
      for (size_t lane = 0; lane < kLanes; ++lane) {
        ASSERT_EQ(ok[lane] != 0, spd::factorLower(scalar[lane].data(), n, ld));
        if (!ok[lane]) continue;
        ++checked;
        const double expected =
            spd::inverseNormComparisonBound(scalar[lane].data(), n, ld, work.data());
        EXPECT_NEAR(bound[lane], expected, 1e-13 * expected)
            << "n " << n << " range " << range << " lane " << lane;
        // ||A^-1||_1 <= the bound: the 1-norm of A^-1's columns, from the scalar factor.
        double inverseNorm = 0;
        for (size_t c = 0; c < n; ++c) {
          std::vector<double> e(n, 0.0);
          e[c] = 1;
          spd::solveLower(scalar[lane].data(), n, ld, e.data());
          spd::solveLowerTransposed(scalar[lane].data(), n, ld, e.data());
          double column = 0;
          for (double v : e) column += std::fabs(v);
          inverseNorm = std::max(inverseNorm, column);
        }
        EXPECT_LE(inverseNorm, bound[lane] * (1 + 1e-6)) << "n " << n << " lane " << lane;
      }
    }
  }
  EXPECT_GE(checked, 100u);  // of 9 sizes x 3 ranges x 4 lanes
}

}  // namespace
}  // namespace voxlink::geostat
