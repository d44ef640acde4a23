// SPDX-License-Identifier: BSD-3-Clause
// Version 2.2 plane extents (format/fragment_extent.h): a roof whose ridge lies inside a voxel.
// A ray just above the ridge misses the real surface; a plane clipped only to its voxel (or only
// to its piece's box) reaches past the ridge and is hit. The same file with its extents cleared
// (what version 2.1 stored) shows the overshoot, so the test can fail.
#include "format/fragment_extent.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "base/crc32c.h"
#include "format/bricked_volume.h"
#include "format/layout.h"
#include "format/validator.h"
#include "pack/open_file.h"
#include "render/voxel_scene_walker.h"
#include "scene/scene_assembly.h"
#include "tests/support/test_util.h"

namespace voxlink::exact {
namespace {

// Helpers at the corners make the grid [-2, 2]^3 with 32 voxels per axis: voxel k's centre lies
// at -2 + k * kSpacing on every axis.
constexpr double kSpacing = 4.0 / 31.0;
// The ridge: x = kRidgeX (centre of voxel column 16), z = kRidgeZ (0.45 into voxel 16); each
// side falls by kSlope in x per unit of z away from it, facing +x.
constexpr double kRidgeX = -2.0 + 16 * kSpacing;
constexpr double kRidgeZ = -2.0 + (16 - 0.5 + 0.45) * kSpacing;
constexpr double kSlope = 0.5;

std::string roofObj() {
  auto x = [](double z) { return kRidgeX - kSlope * std::abs(z - kRidgeZ); };
  const double z0 = kRidgeZ - 1, z1 = kRidgeZ + 1;
  char text[512];
  // Quads (y from -1 to 1) from z0 up to the ridge and from the ridge to z1, normals along +x.
  std::snprintf(text, sizeof text,
                "v %.9g -1 %.9g\nv %.9g 1 %.9g\nv %.9g -1 %.9g\nv %.9g 1 %.9g\n"
                "v %.9g -1 %.9g\nv %.9g 1 %.9g\n"
                "f 1 4 3\nf 1 2 4\nf 3 6 5\nf 3 4 6\n"
                "v -2 -2 -2\nv -1.9 -2 -2\nv -2 -1.9 -2\nv 2 2 2\nv 1.9 2 2\nv 2 1.9 2\n"
                "f 7 8 9\nf 10 12 11\n",
                x(z0), z0, x(z0), z0, x(kRidgeZ), kRidgeZ, x(kRidgeZ), kRidgeZ, x(z1), z1, x(z1),
                z1);
  return text;
}

// The distance to the first surface the ray meets, or -1.
double firstSurface(const render::SceneWalker& walker, const glm::dvec3& origin) {
  double found = -1;
  walker.walk(render::Ray{origin, {0, 0, 1}}, 0, 100, [&](const render::SceneEvent& e) {
    if (e.kind != render::SceneEvent::Kind::kSurface) return true;
    found = e.t;
    return false;
  });
  return found;
}

TEST(FragmentExtent, RoofRidgeInsideAVoxelEndsWhereTheSurfaceEnds) {
  testing::TempDir dir;
  std::ofstream(dir.file("roof.obj")) << roofObj();
  const std::string json = R"({"grid": {"resolution": 32},
      "objects": [{"type": "mesh", "file": ")" +
                           dir.file("roof.obj") + R"("}]})";
  auto description = scene::parseSceneDescription(json, "roof.scene.json");
  ASSERT_TRUE(description) << description.message();
  description->grid.surface = format::SurfaceMode::kPlanes;
  auto built = scene::buildScene(*description);
  ASSERT_TRUE(built) << built.message();
  ASSERT_TRUE(format::writeBrickedVolume(dir.file("roof.vxl"), built->volume));
  auto file = pack::openFile(dir.file("roof.vxl"));
  ASSERT_TRUE(file) << file.message();
  ASSERT_TRUE(format::validateFile(*file)) << format::validateFile(*file).message();
  ASSERT_EQ(file->header().versionMinor, format::kVersionMinorExtents);

  const double start = -1.9;
  {
    const render::VoxelSceneWalker walker(*file);
    // Just below the ridge, on the lower side: the real surface at z = ridge - 0.2 voxel.
    const double below = firstSurface(walker, {kRidgeX - 0.1 * kSpacing, 0.013, start});
    EXPECT_NEAR(below, kRidgeZ - 0.2 * kSpacing - start, 1e-3 * kSpacing);
    // 0.02 voxel above the ridge: no surface. The lower side's plane, extended, crosses the ray
    // 0.04 voxel past the ridge, inside its piece's box (0.45 rounds up to 0.5 voxel).
    EXPECT_EQ(firstSurface(walker, {kRidgeX + 0.02 * kSpacing, 0.013, start}), -1);
  }
  // The same planes with the extents cleared, as a version 2.1 file stores them.
  std::vector<uint8_t> bytes = testing::readBytes(dir.file("roof.vxl"));
  auto& header = *reinterpret_cast<format::FileHeader*>(bytes.data());
  auto* table = reinterpret_cast<format::SectionEntry*>(bytes.data() + header.sectionTableOffset);
  for (uint32_t i = 0; i < header.sectionCount; ++i) {
    if (table[i].id != static_cast<uint32_t>(format::SectionId::kFragments)) continue;
    auto* records = reinterpret_cast<format::FragmentRecord*>(bytes.data() + table[i].offset);
    size_t convex = 0;
    for (uint64_t f = 0; f < header.fragmentCount; ++f) {
      convex += (records[f].extent & format::kExtentConvex) != 0;
      records[f].extent = 0;
    }
    EXPECT_GE(convex, 2u);  // the ridge voxels' two sides
    table[i].crc = crc32c(bytes.data() + table[i].offset, table[i].bytes);
  }
  header.versionMinor = format::kVersionMinorFragments;
  header.headerCrc = 0;
  header.headerCrc = crc32c(bytes.data(), sizeof(format::FileHeader));
  auto old = pack::fileFromBytes(std::move(bytes), "roof21.vxl");
  ASSERT_TRUE(old) << old.message();
  ASSERT_TRUE(format::validateFile(*old)) << format::validateFile(*old).message();
  const render::VoxelSceneWalker walker(*old);
  EXPECT_GT(firstSurface(walker, {kRidgeX + 0.02 * kSpacing, 0.013, start}), 0);
}

}  // namespace
}  // namespace voxlink::exact
