// SPDX-License-Identifier: BSD-3-Clause
// A system the jitter ladder cannot bring under --max-condition ends the local grid solve with
// the one-line "stays singular" error (before the fix: the thread flushed its queue again after
// the failed flush and solved the waiting nodes on unfactored systems: SIGSEGV).
#include <gtest/gtest.h>

#include "geostat/krige_grid.h"
#include "tests/geostat/kriging_test_util.h"

namespace voxlink::geostat {
namespace {

TEST(LocalSingularSystem, AConditionTheJitterCannotMeetIsAnErrorNotACrash) {
  const PointSet s = test::randomPoints(300, 81, 100);
  const Variogram v = test::model(VariogramType::kGaussian, 0, 1, 30);
  const GridSpec grid{{26, 30, 1}, {0, 0, 0}, {4, 3.5, 1}};
  for (unsigned threads : {1u, 2u})
    for (size_t k : {size_t{8}, size_t{64}}) {
      const Kriger kr = test::kriger(s, v, {.maxNeighbours = k, .maxCondition = 10});
      auto summary = krigeGrid(
          kr, grid, [](uint32_t, uint32_t, const double*, const double*) { return Status::ok(); },
          {.threads = threads});
      ASSERT_FALSE(summary) << "k " << k;
      EXPECT_NE(summary.message().find("stays singular"), std::string::npos) << summary.message();
    }
}

}  // namespace
}  // namespace voxlink::geostat
