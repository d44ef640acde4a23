// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/spd_batch_kernels.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace voxlink::geostat
