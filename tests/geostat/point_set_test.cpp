// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/point_set.h"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/support/test_util.h"

namespace voxlink::geostat {
namespace {

TEST(PointSet, ReadsWalkerLakeCsvSkippingNA) {
  VOXLINK_REQUIRE_DATA("geostat/gstat_csv/walker.csv");
  const std::string path = testing::dataPath("geostat/gstat_csv/walker.csv");
  auto v = readPoints(path, {"X", "Y", "", "V"});
  ASSERT_TRUE(v) << v.message();
  EXPECT_EQ(v->size(), 470u);
  EXPECT_EQ(v->dimension, 2);
  EXPECT_EQ(v->coords[2], (Point3{9, 48, 0}));  // third row: 9,48,3,224.4
  EXPECT_DOUBLE_EQ(v->values[2], 224.4);
  auto u = readPoints(path, {"x", "y", "", "u"});  // names match case-insensitively
  ASSERT_TRUE(u) << u.message();
  EXPECT_LT(u->size(), 470u);  // U is NA where it was not measured
  EXPECT_EQ(u->size() + 0, 470u - std::stoul(u->notes.at(0).substr(u->notes[0].find(": ") + 2)));
}

TEST(PointSet, ReadsTheGeoEasSampleFile) {
  VOXLINK_REQUIRE_DATA("geostat/vtk_b_100sampledatawl.sgems");
  auto p = readPoints(testing::dataPath("geostat/vtk_b_100sampledatawl.sgems"),
                      {"X", "Y", "Z", "U-random-samplingtrans"});
  ASSERT_TRUE(p) << p.message();
  EXPECT_EQ(p->size(), 100u);
  EXPECT_EQ(p->dimension, 3);
  EXPECT_EQ(p->coords[0], (Point3{211, 48, 0}));
  EXPECT_DOUBLE_EQ(p->values[0], 126.702804565);
}

TEST(PointSet, BadTablesNameTheLineAndColumn) {
  testing::TempDir dir;
  const std::string path = dir.file("bad.csv");
  std::ofstream(path) << "x,y,v\n1,2,3\n4,oops,6\n";
  auto r = readPoints(path, {"x", "y", "", "v"});
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("line 3"), std::string::npos) << r.message();
  EXPECT_NE(r.message().find("'oops'"), std::string::npos) << r.message();
  auto missing = readPoints(path, {"x", "y", "", "w"});
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.message().find("'w' not found"), std::string::npos) << missing.message();
  std::ofstream(dir.file("short.csv")) << "x,y,v\n1,2\n";
  auto shortRow = readPoints(dir.file("short.csv"), {"x", "y", "", "v"});
  ASSERT_FALSE(shortRow);
  EXPECT_EQ(shortRow.code(), ErrorCode::kTruncated);
  // A row with a field too many, or one short of a column no selection uses: the columns after
  // the change would be shifted.
  std::ofstream(dir.file("long.csv")) << "x,y,v,w\n1,2,3,4\n1,2,3,4,5\n";
  auto longRow = readPoints(dir.file("long.csv"), {"x", "y", "", "v"});
  ASSERT_FALSE(longRow);
  EXPECT_EQ(longRow.code(), ErrorCode::kCorrupt);
  EXPECT_NE(longRow.message().find("line 3: 5 fields, expected 4"), std::string::npos)
      << longRow.message();
  std::ofstream(dir.file("unused.csv")) << "x,y,v,w\n1,2,3\n";
  EXPECT_FALSE(readPoints(dir.file("unused.csv"), {"x", "y", "", "v"}));
}

// Near 1e308 the samples' bounding box was inf wide: "merged ... closer than inf", then
// non-finite predictions.
TEST(PointSet, CoordinatesWhoseDistancesOverflowAreRefused) {
  testing::TempDir dir;
  const std::string path = dir.file("far.csv");
  std::ofstream(path) << "x,y,v\n0,0,1\n1,1e150,2\n-1e308,1,3\n";
  auto r = readPoints(path, {"x", "y", "", "v"});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.message(), path +
                             ": line 4: coordinate column 'x': -1e308 is outside "
                             "[-1e150, 1e150] (distances between samples would overflow)");
  std::ofstream(dir.file("edge.csv")) << "x,y,v\n0,0,1\n1,1e150,2\n-1e150,1,3\n";
  EXPECT_TRUE(readPoints(dir.file("edge.csv"), {"x", "y", "", "v"}));
}

}  // namespace
}  // namespace voxlink::geostat
