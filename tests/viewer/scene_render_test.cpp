// SPDX-License-Identifier: BSD-3-Clause
// Scenes (format version 2) through the GL ray tracer against the float64 scene reference:
// surface fragments on an axis-aligned floor and an oblique semi-transparent wall, exact
// spheres (one emissive, one overlapping the wall), and a volume blob, in one file. Every
// predominant axis, two brick sizes, shadows on and off. Target: PSNR >= 45 dB, as for volumes.
// Also: the reference's spheres against the analytic ray/sphere test, a lit floor against the
// shading formula by hand, and the ray-traced mode (reflection, refraction, shadow rays towards
// point lights) of the same scene with mirror and glass materials against the float64 tracer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

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

constexpr double kTargetPsnr = 45.0;
constexpr uint32_t kDims[3] = {40, 36, 32};

format::MaterialRecord material(float r, float g, float b, float opacity = 1, float specular = 0,
                                float emission = 0) {
  format::MaterialRecord m{};
  m.color[0] = r;
  m.color[1] = g;
  m.color[2] = b;
  m.opacity = opacity;
  m.refractiveIndex = 1;
  m.specular = specular;
  m.shininess = 20;
  for (float& e : m.emission) e = emission;
  return m;
}

struct TestSphere {
  double x, y, z, r;
  uint32_t material;
};

// Voxel (i, j, k) spans [i - 1/2, i + 1/2] (origin 0, spacing 1): the format's rule, brute force.
bool sphereOverlaps(const TestSphere& s, uint32_t i, uint32_t j, uint32_t k) {
  auto axis = [](double c, uint32_t v) {
    const double d = std::max({0.0, (v - 0.5) - c, c - (v + 0.5)});
    return d * d;
  };
  return axis(s.x, i) + axis(s.y, j) + axis(s.z, k) <= s.r * s.r;
}

const TestSphere kSpheres[] = {{20, 18, 16, 6, 2}, {11, 10, 9, 3.5, 3}};

// Floor (y = 2, normal +y), oblique wall (x + z = 44, semi-transparent), two spheres, a blob.
std::vector<format::MaterialRecord> plainMaterials() {
  return {material(0.7f, 0.7f, 0.6f), material(0.9f, 0.2f, 0.2f, 0.6f),
          material(0.2f, 0.3f, 0.9f, 1, 0.5f), material(1.0f, 0.9f, 0.5f, 1, 0, 0.8f)};
}

// The same objects for the ray-traced mode: a half-mirror floor, a semi-transparent glass wall,
// a mirror sphere and an emissive glass sphere.
std::vector<format::MaterialRecord> effectsMaterials() {
  std::vector<format::MaterialRecord> m = plainMaterials();
  m[0].reflectivity = 0.5f;
  m[1].transmission = 0.8f;
  m[1].refractiveIndex = 1.4f;
  m[2].reflectivity = 0.8f;
  m[3].transmission = 0.7f;
  m[3].refractiveIndex = 1.5f;
  m[3].emission[0] = m[3].emission[1] = m[3].emission[2] = 0.3f;
  return m;
}

Result<format::BrickedVolume> makeScene(format::Axis axis, uint32_t brick, bool withSpheres = true,
                                        bool withWall = true, bool withBlob = true,
                                        std::vector<format::MaterialRecord> materials = {}) {
  format::VolumeDescription d;
  d.dims = {kDims[0], kDims[1], kDims[2]};
  d.brickSize = brick;
  d.predominantAxis = axis;
  format::SceneBuilder b(d);
  b.setMaterials(materials.empty() ? plainMaterials() : materials);
  std::vector<format::SphereRecord> spheres;
  for (const TestSphere& s : kSpheres) {
    format::SphereRecord r{};
    r.center[0] = float(s.x);
    r.center[1] = float(s.y);
    r.center[2] = float(s.z);
    r.radius = float(s.r);
    r.material = s.material;
    spheres.push_back(r);
  }
  if (withSpheres) b.setSpheres(spheres);
  const uint16_t up = format::encodeGradient(0.0, 1.0, 0.0);
  const uint16_t oblique = format::encodeGradient(1.0, 0.0, 1.0);
  for (uint32_t k = 0; k < kDims[2]; ++k)
    for (uint32_t j = 0; j < kDims[1]; ++j)
      for (uint32_t i = 0; i < kDims[0]; ++i) {
        if (j == 2)
          b.addSurface(i, j, k, up, 0);
        else if (withWall && std::abs(double(i) + k - 44.0) <= 1.0 && j > 2)
          b.addSurface(i, j, k, oblique, 1);
        if (withSpheres)
          for (uint32_t s = 0; s < 2; ++s)
            if (sphereOverlaps(kSpheres[s], i, j, k)) b.addSphereRef(i, j, k, s);
        const double dx = i - 30.0, dy = j - 9.0, dz = k - 24.0;
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (withBlob && r2 < 20)
          b.addVolumeSample(i, j, k, uint32_t(250 - 5 * r2), format::encodeGradient(-dx, -dy, -dz));
      }
  return b.build("{}");
}

struct Rendered {
  Image gl, reference;
  ImageError error;
};

RenderSettings sceneSettings(bool shadows, uint32_t w = 96, uint32_t h = 80) {
  RenderSettings s;
  s.width = w;
  s.height = h;
  s.shading.shadows = shadows;
  return s;
}

Rendered renderScene(const format::VoxLinkFile& file, const CameraSpec& spec,
                     const RenderSettings& s, const VolumeRenderer** used = nullptr) {
  Rendered out;
  auto renderer = VoxLinkRenderer::create(file);
  EXPECT_TRUE(renderer) << renderer.message();
  if (!renderer) return out;
  const tf::TransferFunction tf = testing::rampTf(100, 60, 0.6, 100, 255);
  (*renderer)->setTransferFunction(tf);
  const SceneReferenceRenderer reference(file, tf);
  const Camera camera = Camera::framing((*renderer)->geometry().worldBox(), spec);
  RenderTarget target;
  const Status st = (*renderer)->render(camera, s, target);
  EXPECT_TRUE(st.isOk()) << (st ? "" : st.message());
  out.gl = target.read();
  out.reference = reference.render(camera, s);
  auto e = compareImages(out.gl, out.reference);
  EXPECT_TRUE(e.isOk());
  if (e) out.error = *e;
  if (used) {
    static std::unique_ptr<VoxLinkRenderer> keep;  // the caller reads its statistics
    keep = std::move(*renderer);
    *used = keep.get();
  }
  return out;
}

double coverage(const Image& image) {
  double sum = 0;
  for (size_t i = 3; i < image.rgba.size(); i += 4) sum += image.rgba[i];
  return sum / (image.rgba.size() / 4);
}

TEST(SceneRender, GlMatchesReferenceOnEveryAxisAndBrickSize) {
  VOXLINK_REQUIRE_GL();
  for (format::Axis axis : {format::Axis::kX, format::Axis::kY, format::Axis::kZ}) {
    for (uint32_t brick : {4u, 8u}) {
      auto built = makeScene(axis, brick);
      ASSERT_TRUE(built) << built.message();
      voxlink::testing::TempDir dir;
      auto file = testing::writeAndOpen(*built, dir.file("scene.vxl"));
      ASSERT_TRUE(file) << file.message();
      for (bool shadows : {false, true}) {
        CameraSpec spec;
        spec.up = UpAxis::kY;
        spec.azimuthDeg = shadows ? 35 : -50;
        spec.elevationDeg = shadows ? 25 : 40;
        const Rendered r = renderScene(*file, spec, sceneSettings(shadows));
        std::printf("axis %d brick %u shadows %d: PSNR %.2f dB, max %.4f\n", int(axis), brick,
                    int(shadows), r.error.psnr, r.error.maxError);
        EXPECT_EQ(r.error.nonFinite, 0u);
        EXPECT_GE(r.error.psnr, kTargetPsnr)
            << "axis " << int(axis) << " brick " << brick << " shadows " << shadows;
        EXPECT_GT(coverage(r.reference), 0.15);
      }
    }
  }
}

TEST(SceneRender, EffectsGlMatchesReferenceOnEveryAxis) {
  VOXLINK_REQUIRE_GL();
  for (format::Axis axis : {format::Axis::kX, format::Axis::kY, format::Axis::kZ}) {
    auto built = makeScene(axis, 8, true, true, true, effectsMaterials());
    ASSERT_TRUE(built) << built.message();
    voxlink::testing::TempDir dir;
    auto file = testing::writeAndOpen(*built, dir.file("effects.vxl"));
    ASSERT_TRUE(file) << file.message();
    RenderSettings s = sceneSettings(false);
    s.effects.reflect = s.effects.refract = s.effects.shadows = true;
    s.lights = {Light{{20, 30, 16}, {0.8, 0.8, 0.7}, false},
                Light{{-30, 60, 50}, {0.4, 0.4, 0.5}, false}};
    s.background = {0.1, 0.15, 0.2};
    CameraSpec spec;
    spec.up = UpAxis::kY;
    spec.azimuthDeg = 35;
    spec.elevationDeg = 25;
    const VolumeRenderer* gl = nullptr;
    const Rendered r = renderScene(*file, spec, s, &gl);
    ASSERT_NE(gl, nullptr);
    const auto stats = gl->lastEffectsStats();
    std::printf("effects, axis %d: PSNR %.2f dB, max %.4f, %d passes, %llu secondary rays\n",
                int(axis), r.error.psnr, r.error.maxError, stats.passes,
                (unsigned long long)stats.secondaryRays);
    EXPECT_EQ(r.error.nonFinite, 0u);
    EXPECT_GE(r.error.psnr, kTargetPsnr) << "axis " << int(axis);
    EXPECT_GT(stats.passes, 2);
    EXPECT_GT(stats.secondaryRays, 1000u);
    EXPECT_EQ(stats.droppedRays, 0u);
    // The paper's bounded passes: rays that stop after one occupied brick and go on in the next
    // pass give the same image.
    s.effects.stepsPerPass = 1;
    const Rendered stepped = renderScene(*file, spec, s, &gl);
    EXPECT_GT(gl->lastEffectsStats().passes, 10);
    EXPECT_EQ(gl->lastEffectsStats().droppedRays, 0u);
    auto same = compareImages(stepped.gl, r.gl);
    ASSERT_TRUE(same);
    EXPECT_GE(same->psnr, 60.0);
    // The effects change the picture: the mirror floor shows more than its diffuse colour.
    s.effects = Effects{};
    s.lights.clear();
    const Rendered plain = renderScene(*file, spec, s);
    auto differ = compareImages(plain.reference, r.reference);
    ASSERT_TRUE(differ);
    EXPECT_LT(differ->psnr, 30.0);
  }
}

TEST(SceneRender, ReferenceSpheresAreExact) {
  // Spheres alone, shading off: a pixel is covered exactly when its ray meets a sphere.
  format::VolumeDescription d;
  d.dims = {kDims[0], kDims[1], kDims[2]};
  format::SceneBuilder b(d);
  b.setMaterials({material(0.5f, 0.5f, 0.5f)});
  std::vector<format::SphereRecord> spheres;
  for (const TestSphere& s : kSpheres) {
    format::SphereRecord r{};
    r.center[0] = float(s.x);
    r.center[1] = float(s.y);
    r.center[2] = float(s.z);
    r.radius = float(s.r);
    spheres.push_back(r);
    for (uint32_t k = 0; k < kDims[2]; ++k)
      for (uint32_t j = 0; j < kDims[1]; ++j)
        for (uint32_t i = 0; i < kDims[0]; ++i)
          if (sphereOverlaps(s, i, j, k)) b.addSphereRef(i, j, k, uint32_t(spheres.size() - 1));
  }
  b.setSpheres(spheres);
  auto scene = b.build();
  ASSERT_TRUE(scene) << scene.message();
  voxlink::testing::TempDir dir;
  auto file = testing::writeAndOpen(*scene, dir.file("spheres.vxl"));
  ASSERT_TRUE(file) << file.message();
  const tf::TransferFunction tf = testing::rampTf(100, 60, 0.6, 100, 255);
  const SceneReferenceRenderer reference(*file, tf);
  RenderSettings s;
  s.width = 120;
  s.height = 100;
  s.shading.enabled = false;
  const Camera camera = Camera::framing({{-0.5, -0.5, -0.5}, {39.5, 35.5, 31.5}}, {});
  uint64_t covered = 0, wrong = 0;
  for (uint32_t y = 0; y < s.height; ++y)
    for (uint32_t x = 0; x < s.width; ++x) {
      const Ray ray = camera.primaryRay(x, y, s.width, s.height);
      bool hits = false;
      for (const TestSphere& t : kSpheres) {
        const glm::dvec3 oc = ray.origin - glm::dvec3(t.x, t.y, t.z);
        const double b2 = glm::dot(oc, ray.direction), c = glm::dot(oc, oc) - t.r * t.r;
        hits = hits || (b2 * b2 - c >= 0 && -b2 + std::sqrt(b2 * b2 - c) > 0);
      }
      const double alpha = reference.traceRay(ray, camera, s)[3];
      covered += hits;
      wrong += hits != (alpha > 0.5);
    }
  EXPECT_GT(covered, 300u);
  EXPECT_EQ(wrong, 0u) << "of " << covered << " covered pixels";
}

TEST(SceneRender, LitFloorFollowsTheShadingFormula) {
  VOXLINK_REQUIRE_GL();
  auto built = makeScene(format::Axis::kZ, 8, false, false, false);  // the floor alone
  ASSERT_TRUE(built);
  voxlink::testing::TempDir dir;
  auto file = testing::writeAndOpen(*built, dir.file("floor.vxl"));
  ASSERT_TRUE(file) << file.message();
  CameraSpec spec;
  spec.up = UpAxis::kY;
  spec.elevationDeg = 60;
  const Rendered r = renderScene(*file, spec, sceneSettings(false, 64, 64));
  // The centre pixel sees the floor: colour = (ambient + diffuse * n.l) * Kd with n = +y.
  auto renderer = VoxLinkRenderer::create(*file);
  ASSERT_TRUE(renderer);
  const Camera camera = Camera::framing((*renderer)->geometry().worldBox(), spec);
  const RenderSettings settings;
  const auto& l = settings.shading.lightDirection;
  const glm::dvec3 toLight =
      glm::normalize(camera.toWorld(glm::normalize(glm::dvec3(l[0], l[1], l[2]))));
  const double expected =
      (settings.shading.ambient + settings.shading.diffuse * std::max(toLight.y, 0.0)) * 0.7;
  const float* p = r.gl.pixel(32, 32);
  EXPECT_NEAR(p[0], expected, 2e-3);
  EXPECT_NEAR(p[3], 1.0, 1e-6);
  EXPECT_GE(r.error.psnr, kTargetPsnr);
}

TEST(SceneRender, TrilinearSamplingOfAScene) {
  VOXLINK_REQUIRE_GL();
  auto built = makeScene(format::Axis::kZ, 8);
  ASSERT_TRUE(built);
  voxlink::testing::TempDir dir;
  auto file = testing::writeAndOpen(*built, dir.file("scene.vxl"));
  ASSERT_TRUE(file);
  auto renderer = VoxLinkRenderer::create(*file);
  ASSERT_TRUE(renderer);
  RenderSettings s;
  s.width = s.height = 16;
  s.sampling = Sampling::kTrilinear;
  RenderTarget target;
  const Status st =
      (*renderer)->render(Camera::framing((*renderer)->geometry().worldBox(), {}), s, target);
  ASSERT_FALSE(st.isOk());
  EXPECT_NE(st.message().find("voxel sampling"), std::string::npos) << st.message();
}

}  // namespace
}  // namespace voxlink::render::gl
