// SPDX-License-Identifier: BSD-3-Clause
// Fragment lists (format version 2.1/2.2) through the GL ray tracer against the float64 scene
// reference (render/voxel_scene_walker.cpp): a floor plane (half of every other voxel cut away
// by its extent), a wall thinner than a voxel with a plane per side and a material per side, and a
// sphere crossing the wall, as planes; the same floor and wall as referenced triangles. Plain, with
// shadows, and ray traced.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "format/fragment_extent.h"
#include "format/gradient_codec.h"
#include "format/scene_builder.h"
#include "render/gl/render_target.h"
#include "render/gl/voxlink_renderer.h"
#include "render/scene_reference_renderer.h"
#include "tests/support/test_util.h"
#include "tests/viewer/gl_test_context.h"
#include "tests/viewer/volume_fixtures.h"

namespace voxlink::render::gl {

namespace {

using format::FragmentRecord;
using format::SurfaceMode;

constexpr uint32_t kDims[3] = {40, 36, 32};
constexpr double kWall = 44.0;  // the wall's front side: x + z = 44, its back 0.4 voxel behind

format::MaterialRecord material(float r, float g, float b, float reflectivity = 0) {
  format::MaterialRecord m{};
  m.color[0] = r;
  m.color[1] = g;
  m.color[2] = b;
  m.opacity = 1;
  m.refractiveIndex = 1;
  m.reflectivity = reflectivity;
  m.specular = 0.3f;
  m.shininess = 20;
  return m;
}

bool onFloor(uint32_t j) { return j == 2; }
bool onWall(uint32_t i, uint32_t j, uint32_t k) {
  return j > 2 && std::abs(double(i) + k - kWall) <= 1.0;
}

// Plane through world point q with unit normal n, relative to voxel (i, j, k)'s centre (origin
// 0, spacing 1: the centre is (i, j, k)).
FragmentRecord plane(glm::dvec3 n, glm::dvec3 q, uint32_t i, uint32_t j, uint32_t k, uint16_t m) {
  n = glm::normalize(n);
  FragmentRecord r{};
  r.word = format::surfaceWord(format::encodeGradient(n.x, n.y, n.z), m);
  const double offset = glm::dot(n, q - glm::dvec3(i, j, k));
  r.offset = int16_t(std::lround(offset / format::kPlaneOffsetUnit));
  return r;
}

format::TriangleRecord triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t m) {
  format::TriangleRecord t{};
  const glm::vec3 v[3] = {a, b, c};
  for (int k = 0; k < 3; ++k)
    for (int x = 0; x < 3; ++x) t.vertices[3 * k + x] = v[k][x];
  t.material = m;
  return t;
}

Result<format::BrickedVolume> makeScene(SurfaceMode mode, format::Axis axis) {
  format::VolumeDescription d;
  d.dims = {kDims[0], kDims[1], kDims[2]};
  d.predominantAxis = axis;
  format::SceneBuilder b(d);
  b.setMaterials({material(0.7f, 0.7f, 0.6f, 0.4f), material(0.9f, 0.2f, 0.2f),
                  material(0.2f, 0.3f, 0.9f), material(0.3f, 0.8f, 0.3f, 0.5f)});
  b.setSurfaceMode(mode);
  const glm::dvec3 wallNormal(1, 0, 1);
  if (mode == SurfaceMode::kTriangles) {
    const float y = 2.2f, top = 36, w = float(kWall);
    b.setTriangles({triangle({-1, y, -1}, {-1, y, 33}, {41, y, -1}, 0),
                    triangle({41, y, -1}, {-1, y, 33}, {41, y, 33}, 0),
                    triangle({w, 3, 0}, {w, top, 0}, {w - 32, 3, 32}, 1),
                    triangle({w - 32, 3, 32}, {w, top, 0}, {w - 32, top, 32}, 1)});
  } else {
    format::SphereRecord s{};
    s.center[0] = 30;
    s.center[1] = 14;
    s.center[2] = 14;
    s.radius = 4;
    s.material = 3;
    b.setSpheres({s});
  }
  for (uint32_t k = 0; k < kDims[2]; ++k)
    for (uint32_t j = 0; j < kDims[1]; ++j)
      for (uint32_t i = 0; i < kDims[0]; ++i) {
        const bool floor = onFloor(j), wall = onWall(i, j, k);
        if (!floor && !wall) continue;
        b.addSurface(i, j, k, format::encodeGradient(0.0, 1.0, 0.0), floor ? 0 : 1);
        if (mode == SurfaceMode::kTriangles) {
          const uint32_t floorRefs[] = {0, 1}, wallRefs[] = {2, 3};
          b.addTriangleRefs(i, j, k, floor ? floorRefs : wallRefs);
          continue;
        }
        if (floor) {
          // Version 2.2 extents: every other floor voxel keeps only x in [0, 0.5] of the voxel
          // (seen along y: u is z, v is x), a checkerboard of holes.
          FragmentRecord f = plane({0, 1, 0}, {0, 2.2, 0}, i, j, k, 0);
          if ((i + k) % 2 == 0) f.extent = format::encodeExtent(1, {0, 0}, {1, 0.5});
          b.addFragments(i, j, k, std::span(&f, 1));
        } else {
          // The wall's two sides lie behind each other: a convex pair, clipped by each other.
          FragmentRecord sides[] = {
              plane(wallNormal, {kWall, 0, 0}, i, j, k, 1),
              plane(-wallNormal, {kWall - 0.4 * std::sqrt(2.0), 0, 0}, i, j, k, 2)};
          for (FragmentRecord& side : sides)
            side.extent = format::encodeExtent(0, {0, 0}, {1, 1}, /*convex=*/true);
          b.addFragments(i, j, k, sides);
        }
        const double dx = i - 30.0, dy = j - 14.0, dz = k - 14.0;
        if (mode == SurfaceMode::kPlanes && std::sqrt(dx * dx + dy * dy + dz * dz) < 6)
          b.addSphereRef(i, j, k, 0);
      }
  // The sphere's own shell beyond the wall and floor voxels.
  if (mode == SurfaceMode::kPlanes)
    for (uint32_t k = 8; k < 21; ++k)
      for (uint32_t j = 8; j < 21; ++j)
        for (uint32_t i = 24; i < 37; ++i) {
          const double dx = i - 30.0, dy = j - 14.0, dz = k - 14.0;
          const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
          if (r > 2.2 && r < 5.8 && !onWall(i, j, k) && !onFloor(j)) b.addSphereRef(i, j, k, 0);
        }
  return b.build("{}");
}

// Share of the image's alpha: how much of it shows something.
double coverage(const render::Image& image) {
  double sum = 0;
  for (size_t i = 3; i < image.rgba.size(); i += 4) sum += image.rgba[i];
  return sum / double(image.rgba.size() / 4);
}

TEST(FragmentListsRender, GlMatchesTheFloat64Walker) {
  VOXLINK_REQUIRE_GL();
  for (SurfaceMode mode : {SurfaceMode::kPlanes, SurfaceMode::kTriangles}) {
    for (format::Axis axis : {format::Axis::kX, format::Axis::kZ}) {
      auto built = makeScene(mode, axis);
      ASSERT_TRUE(built) << built.message();
      voxlink::testing::TempDir dir;
      auto file = testing::writeAndOpen(*built, dir.file("scene.vxl"));
      ASSERT_TRUE(file) << file.message();
      for (int variant = 0; variant < 3; ++variant) {  // plain, shadows, ray traced
        render::RenderSettings s;
        s.width = s.height = 128;
        s.shading.shadows = variant == 1;
        if (variant == 2) {
          s.effects.reflect = s.effects.shadows = true;
          s.lights = {render::Light{{34, 30, 30}, {0.9, 0.9, 0.8}, false}};
        }
        // Both sides of the wall: from the front (azimuth 35) and from behind (-145).
        for (double azimuth : {35.0, -145.0}) {
          render::CameraSpec spec;
          spec.up = render::UpAxis::kY;
          spec.azimuthDeg = azimuth;
          spec.elevationDeg = 25;
          auto renderer = VoxLinkRenderer::create(*file);
          ASSERT_TRUE(renderer) << renderer.message();
          const tf::TransferFunction tf = testing::rampTf(100, 60, 0.6, 100, 255);
          (*renderer)->setTransferFunction(tf);
          const render::SceneReferenceRenderer reference(*file, tf);
          const render::Camera camera =
              render::Camera::framing((*renderer)->geometry().worldBox(), spec);
          RenderTarget target;
          ASSERT_TRUE((*renderer)->render(camera, s, target));
          const render::Image gl = target.read();
          const render::Image want = reference.render(camera, s);
          auto e = render::compareImages(gl, want);
          ASSERT_TRUE(e);
          std::printf("%s, axis %d, variant %d, azimuth %.0f: PSNR %.2f dB, %llu pixels off\n",
                      mode == SurfaceMode::kPlanes ? "planes" : "triangles", int(axis), variant,
                      azimuth, e->psnr, (unsigned long long)e->pixelsOver);
          EXPECT_EQ(e->nonFinite, 0u);
          EXPECT_GE(e->psnr, 45.0);
          EXPECT_GT(coverage(want), 0.1);
        }
      }
    }
  }
}

}  // namespace
}  // namespace voxlink::render::gl
