// SPDX-License-Identifier: BSD-3-Clause
// Version 2.1 files: per surface voxel a list of planes (FRAG) or triangle references (TRID into
// TRIS) beside the voxel's SURF word. Round trips (plain and packed), the builder's refusals, and
// damaged lists against the validator's messages.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "base/crc32c.h"
#include "format/bricked_volume.h"
#include "format/fragment_extent.h"
#include "format/gradient_codec.h"
#include "format/scene_builder.h"
#include "format/surface_mode.h"
#include "format/validator.h"
#include "format/voxlink_file.h"
#include "pack/open_file.h"
#include "pack/packed_file.h"
#include "report/footprint.h"
#include "tests/support/test_util.h"

namespace voxlink::format {
namespace {

MaterialRecord grey() {
  MaterialRecord m{};
  m.color[0] = m.color[1] = m.color[2] = 0.5f;
  m.opacity = 1;
  m.refractiveIndex = 1;
  return m;
}

VolumeDescription smallGrid() {
  VolumeDescription d;
  d.dims = {16, 12, 10};
  d.brickSize = 8;
  return d;
}

FragmentRecord plane(double x, double y, double z, int16_t offset, uint16_t material = 0) {
  FragmentRecord r{};
  r.word = surfaceWord(encodeGradient(x, y, z), material);
  r.offset = offset;
  return r;
}

TriangleRecord triangle(float z, uint32_t material = 0) {
  TriangleRecord t{};
  const float v[9] = {0, 0, z, 4, 0, z, 0, 4, z};
  std::memcpy(t.vertices, v, sizeof v);
  t.material = material;
  return t;
}

// Two surface voxels: (1, 2, 3) with the two sides of a sheet, (5, 5, 5) with one plane.
SceneBuilder planesScene(size_t firstListLength = 2) {
  SceneBuilder b(smallGrid());
  b.setMaterials({grey(), grey()});
  b.setSurfaceMode(SurfaceMode::kPlanes);
  b.addSurface(1, 2, 3, encodeGradient(0.0, 0.0, 1.0), 0);
  std::vector<FragmentRecord> sheet;
  for (size_t i = 0; i < firstListLength; ++i)
    sheet.push_back(i % 2 ? plane(0, 0, -1, 400, 1) : plane(0, 0, 1, -400, 0));
  b.addFragments(1, 2, 3, sheet);
  b.addSurface(5, 5, 5, encodeGradient(1.0, 0.0, 0.0), 1);
  FragmentRecord one = plane(1, 0, 0, 17, 1);
  one.extent = encodeExtent(0, {0.25, 0.5}, {0.75, 1.0});
  b.addFragments(5, 5, 5, std::span(&one, 1));
  return b;
}

Result<VoxLinkFile> writeAndOpen(const SceneBuilder& b, const std::string& path) {
  VOXLINK_ASSIGN_OR_RETURN(BrickedVolume built, b.build("{}"));
  VOXLINK_RETURN_IF_ERROR(writeBrickedVolume(path, built));
  return VoxLinkFile::open(path);
}

TEST(FragmentFormat, PlanesRoundTripPlainAndPacked) {
  testing::TempDir dir;
  auto f = writeAndOpen(planesScene(), dir.file("planes.vxl"));
  ASSERT_TRUE(f) << f.message();
  ASSERT_TRUE(validateFile(*f)) << validateFile(*f).message();
  EXPECT_EQ(f->header().versionMajor, kVersionMajorScene);
  EXPECT_EQ(f->header().versionMinor, kVersionMinorExtents);
  EXPECT_EQ(f->surfaceMode(), SurfaceMode::kPlanes);
  EXPECT_EQ(f->header().fragmentCount, 3u);
  // File order is (z, y, x) by brick: (1, 2, 3) before (5, 5, 5).
  const auto starts = f->fragmentStarts();
  ASSERT_EQ(starts.size(), 3u);
  EXPECT_EQ(starts[0], 0u);
  EXPECT_EQ(starts[1], 2u);
  EXPECT_EQ(starts[2], 3u);
  EXPECT_EQ(f->fragments()[0].offset, -400);
  EXPECT_EQ(surfaceMaterial(f->fragments()[1].word), 1);
  EXPECT_EQ(f->fragments()[2].offset, 17);
  EXPECT_EQ(f->fragments()[2].extent, encodeExtent(0, {0.25, 0.5}, {0.75, 1.0}));
  // `voxlink info` names the mode and counts the lists.
  const report::FootprintReport footprint = report::computeFootprint(*f);
  ASSERT_TRUE(footprint.scene);
  EXPECT_EQ(footprint.scene->surfaceMode, "planes");
  EXPECT_EQ(footprint.scene->fragments, 3u);
  EXPECT_NE(report::footprintTable(footprint).find(
                "surface mode planes: 3 fragments, 1.500 per surface voxel"),
            std::string::npos)
      << report::footprintTable(footprint);
  ASSERT_TRUE(pack::packFile(*f, dir.file("planes.packed.vxl")));
  auto unpacked =
      pack::unpackFile(testing::readBytes(dir.file("planes.packed.vxl")), "p", uint64_t{1} << 30);
  ASSERT_TRUE(unpacked) << unpacked.message();
  ASSERT_EQ(unpacked->fileBytes(), f->fileBytes());
  EXPECT_EQ(std::memcmp(unpacked->bytes().data(), f->bytes().data(), f->fileBytes()), 0);
}

TEST(FragmentFormat, TrianglesRoundTrip) {
  SceneBuilder b(smallGrid());
  b.setMaterials({grey()});
  b.setSurfaceMode(SurfaceMode::kTriangles);
  b.setTriangles({triangle(1), triangle(2), triangle(3)});
  b.addSurface(2, 2, 2, encodeGradient(0.0, 0.0, 1.0), 0);
  const uint32_t refs[] = {0, 2};
  b.addTriangleRefs(2, 2, 2, refs);
  testing::TempDir dir;
  auto f = writeAndOpen(b, dir.file("triangles.vxl"));
  ASSERT_TRUE(f) << f.message();
  ASSERT_TRUE(validateFile(*f)) << validateFile(*f).message();
  EXPECT_EQ(f->surfaceMode(), SurfaceMode::kTriangles);
  EXPECT_EQ(f->header().triangleCount, 3u);
  ASSERT_EQ(f->triangleRefs().size(), 2u);
  EXPECT_EQ(f->triangleRefs()[1], 2u);
  EXPECT_EQ(f->triangles()[2].vertices[2], 3.0f);
  const report::FootprintReport footprint = report::computeFootprint(*f);
  ASSERT_TRUE(footprint.scene);
  EXPECT_EQ(footprint.scene->surfaceMode, "triangles");
  EXPECT_NE(report::footprintJson(footprint).find(R"("triangles": 3)"), std::string::npos)
      << report::footprintJson(footprint);
  EXPECT_NE(report::footprintTable(footprint).find(
                "surface mode triangles: 3 triangles, 2 references, 2.000 per surface voxel"),
            std::string::npos)
      << report::footprintTable(footprint);
}

// `scene build --surface triangles` on a scene without meshes (a protein alone) wrote a file
// with no triangles that every reader refused ("header.triangleCount: 0 with surfaceMode 2").
TEST(FragmentFormat, TrianglesModeWithoutSurfaceVoxelsOpens) {
  SceneBuilder b(smallGrid());
  b.setMaterials({grey()});
  b.setSurfaceMode(SurfaceMode::kTriangles);
  SphereRecord atom{};
  atom.center[0] = atom.center[1] = atom.center[2] = 3;
  atom.radius = 0.5f;
  b.setSpheres({atom});
  b.addSphereRef(3, 3, 3, 0);
  testing::TempDir dir;
  auto f = writeAndOpen(b, dir.file("no-meshes.vxl"));
  ASSERT_TRUE(f) << f.message();
  ASSERT_TRUE(validateFile(*f)) << validateFile(*f).message();
  EXPECT_EQ(f->surfaceMode(), SurfaceMode::kTriangles);
  EXPECT_EQ(f->header().triangleCount, 0u);
  EXPECT_EQ(f->header().surfaceVoxelCount, 0u);
  EXPECT_EQ(f->header().sphereVoxelCount, 1u);
}

TEST(FragmentFormat, BuilderRefusesWhatTheFormatCannotSay) {
  {
    auto r = planesScene(kMaxFragmentsPerVoxel + 1).build();
    ASSERT_FALSE(r);
    EXPECT_EQ(r.message(), "voxel (1, 2, 3): 256 fragments; the format holds 1 to 255 per voxel");
  }
  EXPECT_TRUE(planesScene(kMaxFragmentsPerVoxel).build());
  {
    SceneBuilder b(smallGrid());
    b.setMaterials({grey()});
    b.setSurfaceMode(SurfaceMode::kPlanes);
    b.addSurface(1, 1, 1, encodeGradient(0.0, 0.0, 1.0), 0);
    auto r = b.build();
    ASSERT_FALSE(r);
    EXPECT_EQ(r.message(), "voxel (1, 1, 1) has a surface fragment but no fragment list");
  }
  {
    SceneBuilder b(smallGrid());
    b.setMaterials({grey()});
    b.setSurfaceMode(SurfaceMode::kPlanes);
    b.addSurface(1, 1, 1, encodeGradient(0.0, 0.0, 1.0), 0);
    FragmentRecord bad = plane(0, 0, 1, 0);
    bad.extent = 3;  // axis 3
    b.addFragments(1, 1, 1, std::span(&bad, 1));
    auto r = b.build();
    ASSERT_FALSE(r);
    EXPECT_EQ(r.message(), "voxel (1, 1, 1): fragment extent 0x3 is not a box");
  }
  {
    SceneBuilder b(smallGrid());
    b.setMaterials({grey()});
    b.setSurfaceMode(SurfaceMode::kTriangles);
    b.setTriangles({triangle(1)});
    b.addSurface(1, 1, 1, encodeGradient(0.0, 0.0, 1.0), 0);
    const uint32_t refs[] = {1};
    b.addTriangleRefs(1, 1, 1, refs);
    auto r = b.build();
    ASSERT_FALSE(r);
    EXPECT_NE(r.message().find("triangle 1 is not ascending or not in the table of 1"),
              std::string::npos)
        << r.message();
  }
}

TEST(FragmentFormat, ModeNamesParseBack) {
  for (std::string_view name : kSurfaceModeNames)
    EXPECT_EQ(surfaceModeName(*parseSurfaceMode(name)), name);
  EXPECT_FALSE(parseSurfaceMode("voxels"));
}

// Damages a field of a valid planes file, reseals the checksums, and expects the named field.
class FragmentBadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    auto built = planesScene(kMaxFragmentsPerVoxel).build("{}");
    ASSERT_TRUE(built);
    ASSERT_TRUE(writeBrickedVolume(dir_.file("good.vxl"), *built).isOk());
    bytes_ = testing::readBytes(dir_.file("good.vxl"));
  }
  FileHeader& header() { return *reinterpret_cast<FileHeader*>(bytes_.data()); }
  template <typename T>
  T* section(SectionId id) {
    auto* table = reinterpret_cast<SectionEntry*>(bytes_.data() + header().sectionTableOffset);
    for (uint32_t i = 0; i < header().sectionCount; ++i)
      if (table[i].id == static_cast<uint32_t>(id))
        return reinterpret_cast<T*>(bytes_.data() + table[i].offset);
    return nullptr;
  }
  std::string problem() {
    auto* table = reinterpret_cast<SectionEntry*>(bytes_.data() + header().sectionTableOffset);
    for (uint32_t i = 0; i < header().sectionCount; ++i)
      table[i].crc = crc32c(bytes_.data() + table[i].offset, table[i].bytes);
    header().headerCrc = 0;
    header().headerCrc = crc32c(bytes_.data(), sizeof(FileHeader));
    auto f = pack::fileFromBytes(bytes_, "bad.vxl");
    if (!f) return f.message();
    auto v = validateFile(*f);
    return v ? "" : v.message();
  }
  testing::TempDir dir_;
  std::vector<uint8_t> bytes_;
};

TEST_F(FragmentBadInput, GoodFileValidates) { EXPECT_EQ(problem(), ""); }

TEST_F(FragmentBadInput, ListLongerThanTheFormatAllows) {
  section<uint32_t>(SectionId::kFragmentStart)[1] = 256;  // voxel 0: 256, voxel 1: none
  EXPECT_EQ(problem(),
            "bad.vxl: section FROF: surface voxel 0 has fragments [0, 256) of 256 (a surface "
            "voxel has 1 to 255)");
}

TEST_F(FragmentBadInput, FragmentReservedBitsSet) {
  section<FragmentRecord>(SectionId::kFragments)[3].extent = 0x8000;
  EXPECT_EQ(problem(),
            "bad.vxl: section FRAG: fragment 3.extent 0x8000 is not a box (axis 3, bit 15 set, "
            "or an interval under 1/8 voxel)");
}

TEST_F(FragmentBadInput, FragmentExtentAxisThree) {
  section<FragmentRecord>(SectionId::kFragments)[2].extent = 3;
  EXPECT_EQ(problem(),
            "bad.vxl: section FRAG: fragment 2.extent 0x3 is not a box (axis 3, bit 15 set, or an "
            "interval under 1/8 voxel)");
}

TEST_F(FragmentBadInput, FragmentExtentIntervalUnderAnEighth) {
  // u from 4/8 up to 4/8 below the top: empty.
  section<FragmentRecord>(SectionId::kFragments)[1].extent = uint16_t((4 << 2) | (4 << 5));
  EXPECT_EQ(problem(),
            "bad.vxl: section FRAG: fragment 1.extent 0x90 is not a box (axis 3, bit 15 set, or "
            "an interval under 1/8 voxel)");
}

TEST_F(FragmentBadInput, FragmentExtentInAVersion21File) {
  header().versionMinor = kVersionMinorFragments;
  section<FragmentRecord>(SectionId::kFragments)[0].extent = 1;
  EXPECT_EQ(problem(),
            "bad.vxl: section FRAG: fragment 0.extent is not zero in a version 2.1 file");
}

TEST_F(FragmentBadInput, Version21PlanesWithoutExtentsStillValidate) {
  header().versionMinor = kVersionMinorFragments;
  section<FragmentRecord>(SectionId::kFragments)[kMaxFragmentsPerVoxel].extent = 0;
  EXPECT_EQ(problem(), "");
}

TEST(FragmentExtent, CodesRoundOutwardsAndHoldTheirBox) {
  // A piece over u in [0.3, 0.6], v in [0, 1] seen along y: u is z, v is x.
  const uint16_t code = encodeExtent(1, {0.3, 0.0}, {0.6, 1.0});
  ASSERT_TRUE(isValidExtent(code));
  const FragmentExtent e = decodeExtent(code);
  EXPECT_EQ(e.axis, 1);
  EXPECT_DOUBLE_EQ(e.lo[0], 0.25);
  EXPECT_DOUBLE_EQ(e.hi[0], 0.625);
  EXPECT_DOUBLE_EQ(e.lo[1], 0.0);
  EXPECT_DOUBLE_EQ(e.hi[1], 1.0);
  EXPECT_TRUE(extentHolds(e, {0.0, 0.9, 0.3}));
  EXPECT_FALSE(extentHolds(e, {0.5, 0.5, 0.7}));  // z beyond the piece
  EXPECT_FALSE(extentHolds(e, {0.5, 0.5, 0.2}));
  // Bounds on the voxel's faces hold points that rounded just outside.
  EXPECT_TRUE(extentHolds(e, {-1e-12, 0.5, 0.3}));
  EXPECT_TRUE(extentHolds(decodeExtent(0), {1 + 1e-12, -1e-12, 1 + 1e-12}));
  // A piece thinner than an eighth keeps an eighth; the whole voxel is code 0 on axis 0.
  EXPECT_TRUE(isValidExtent(encodeExtent(2, {0.5, 1.0}, {0.5, 1.0})));
  EXPECT_EQ(encodeExtent(0, {0, 0}, {1, 1}), 0);
  EXPECT_FALSE(isValidExtent(0x8000));
  EXPECT_TRUE(decodeExtent(encodeExtent(1, {0, 0}, {1, 1}, true)).convex);
  EXPECT_FALSE(decodeExtent(encodeExtent(1, {0, 0}, {1, 1}, false)).convex);
}

TEST_F(FragmentBadInput, FragmentMaterialOutOfTable) {
  section<FragmentRecord>(SectionId::kFragments)[0].word = surfaceWord(0, 7);
  EXPECT_EQ(problem(), "bad.vxl: section FRAG: fragment 0 names material 7 of 2");
}

TEST_F(FragmentBadInput, UnknownSurfaceMode) {
  header().surfaceMode = 3;
  EXPECT_EQ(problem(),
            "bad.vxl: header.surfaceMode: 3 is not a known surface mode (0 mean, 1 planes, 2 "
            "triangles)");
}

TEST_F(FragmentBadInput, FragmentListsInAVersion20File) {
  header().versionMinor = 0;
  EXPECT_EQ(problem(), "bad.vxl: header.versionMinor: 0 but surfaceMode 1 needs version 2.1");
}

}  // namespace
}  // namespace voxlink::format
