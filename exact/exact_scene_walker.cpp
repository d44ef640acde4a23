// SPDX-License-Identifier: BSD-3-Clause
#include "exact/exact_scene_walker.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "exact/detail/sphere_roots.h"
#include "geometry/voxel_grid.h"
#include "render/render_model.h"

namespace voxlink::exact {

namespace {

// A reported hit: geometry, primitive and, for spheres, which root (0 near, 1 far).
uint64_t hitKey(unsigned geometry, unsigned primitive, unsigned root) {
  return (uint64_t(geometry) << 40) | (uint64_t(primitive) << 1) | root;
}

glm::dvec3 vertex(const geometry::TriangleMesh& m, uint32_t v) {
  return {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]};
}

glm::dvec3 sphereCenter(const geometry::Sphere& s) {
  return {s.center[0], s.center[1], s.center[2]};
}

std::string embreeError(RTCDevice device, const char* what) {
  return std::string("Embree: ") + what + " failed (error " +
         std::to_string(int(rtcGetDeviceError(device))) + ")";
}

}  // namespace

// Embree hands the context pointer back to the callbacks; the walk's own state follows it.
struct ExactSceneWalker::WalkContext {
  RTCIntersectContext rtc;  // must stay the first member
  const ExactSceneWalker* walker;
  glm::dvec3 origin, direction;  // the double ray; Embree sees it rounded to float
  std::vector<uint64_t> reported;
  bool wasReported(uint64_t key) const {
    return std::find(reported.begin(), reported.end(), key) != reported.end();
  }
};

Result<std::unique_ptr<ExactSceneWalker>> ExactSceneWalker::open(
    const scene::SceneDescription& scene, uint32_t resolution) {
  VOXLINK_ASSIGN_OR_RETURN(scene::PlacedScene placed, scene::placeSceneGeometry(scene));
  if (!placed.volumes.empty())
    return makeError(ErrorCode::kUnsupported, scene.path,
                     ": objects: the exact tracer takes meshes and spheres only, not a volume (",
                     placed.volumes.front()->path, ")");
  if (placed.mesh.triangleCount() == 0 && placed.spheres.empty())
    return makeError(ErrorCode::kInvalidArgument, scene.path,
                     ": objects: the scene holds no geometry");
  VOXLINK_ASSIGN_OR_RETURN(
      geometry::VoxelGrid grid,
      geometry::fitGrid(placed.bounds, resolution ? resolution : scene.grid.resolution));
  render::Box box;
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = grid.origin[a] - 0.5 * grid.spacing;
    box.hi[a] = grid.origin[a] + (double(grid.dims[a]) - 0.5) * grid.spacing;
  }
  return create(std::move(placed), box);
}

Result<std::unique_ptr<ExactSceneWalker>> ExactSceneWalker::create(scene::PlacedScene placed,
                                                                   const render::Box& bounds) {
  std::unique_ptr<ExactSceneWalker> w(new ExactSceneWalker());
  w->placed_ = std::move(placed);
  w->box_ = bounds;
  w->epsilon_ = 1e-6 * glm::length(bounds.hi - bounds.lo);
  if (!(w->epsilon_ > 0) || !std::isfinite(w->epsilon_))
    return makeError(ErrorCode::kInvalidArgument, "exact tracer: empty or non-finite bounds");
  const size_t materialCount = w->placed_.materials.size();
  for (uint16_t m : w->placed_.mesh.triangleMaterials)
    if (m >= materialCount)
      return makeError(ErrorCode::kInvalidArgument, "exact tracer: triangle material ", m,
                       " is not in the table of ", materialCount);
  for (const geometry::Sphere& s : w->placed_.spheres)
    if (s.material >= materialCount)
      return makeError(ErrorCode::kInvalidArgument, "exact tracer: sphere material ", s.material,
                       " is not in the table of ", materialCount);
  VOXLINK_RETURN_IF_ERROR(w->build());
  return w;
}

ExactSceneWalker::~ExactSceneWalker() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

Status ExactSceneWalker::build() {
  device_ = rtcNewDevice(nullptr);
  if (!device_) return makeError(ErrorCode::kUnsupported, embreeError(nullptr, "rtcNewDevice"));
  scene_ = rtcNewScene(device_);
  // Robust traversal: no rays slip between triangles that share an edge.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  const geometry::TriangleMesh& mesh = placed_.mesh;
  faceNormals_.resize(mesh.triangleCount());
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const glm::dvec3 a = vertex(mesh, mesh.triangles[3 * t]);
    const glm::dvec3 b = vertex(mesh, mesh.triangles[3 * t + 1]);
    const glm::dvec3 c = vertex(mesh, mesh.triangles[3 * t + 2]);
    const glm::dvec3 n = glm::cross(b - a, c - a);  // the voxelizer's orientation
    const double length = glm::length(n);
    faceNormals_[t] = length > 0 ? n / length : glm::dvec3(0.0);
  }
  if (mesh.triangleCount() > 0) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree's own buffers: padded for its vector loads, which a std::vector is not.
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertexCount()));
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.triangleCount()));
    if (!vertices || !indices) {
      rtcReleaseGeometry(g);
      return makeError(ErrorCode::kTooLarge, embreeError(device_, "mesh buffer allocation"));
    }
    std::copy(mesh.positions.begin(), mesh.positions.end(), vertices);
    std::copy(mesh.triangles.begin(), mesh.triangles.end(), indices);
    rtcSetGeometryIntersectFilterFunction(g, skipReported);
    rtcCommitGeometry(g);
    meshGeometry_ = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
  }
  if (!placed_.spheres.empty()) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, unsigned(placed_.spheres.size()));
    rtcSetGeometryUserData(g, this);
    rtcSetGeometryBoundsFunction(g, sphereBounds, nullptr);
    rtcSetGeometryIntersectFunction(g, sphereIntersect);
    rtcCommitGeometry(g);
    sphereGeometry_ = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene_);
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
    return makeError(ErrorCode::kTooLarge, embreeError(device_, "building the scene"));
  return Status::ok();
}

void ExactSceneWalker::sphereBounds(const RTCBoundsFunctionArguments* args) {
  const auto* w = static_cast<const ExactSceneWalker*>(args->geometryUserPtr);
  const geometry::Sphere& s = w->placed_.spheres[args->primID];
  // Widened by a float ulp or so: the box must hold the sphere after rounding.
  const float r =
      s.radius * (1.0f + 1e-6f) +
      1e-6f * std::max({std::abs(s.center[0]), std::abs(s.center[1]), std::abs(s.center[2])});
  RTCBounds* b = args->bounds_o;
  b->lower_x = s.center[0] - r;
  b->lower_y = s.center[1] - r;
  b->lower_z = s.center[2] - r;
  b->upper_x = s.center[0] + r;
  b->upper_y = s.center[1] + r;
  b->upper_z = s.center[2] + r;
}

// The nearest root inside [tnear, tfar] that has not been reported yet, computed in double from
// the walk's own ray.
void ExactSceneWalker::sphereIntersect(const RTCIntersectFunctionNArguments* args) {
  if (args->N != 1 || !args->valid[0]) return;
  const auto* ctx = reinterpret_cast<const WalkContext*>(args->context);
  const ExactSceneWalker* w = ctx->walker;
  const geometry::Sphere& s = w->placed_.spheres[args->primID];
  const auto roots = sphereRoots(ctx->origin, ctx->direction, sphereCenter(s), s.radius);
  if (!roots) return;
  auto* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
  for (unsigned root = 0; root < 2; ++root) {
    const double t = (*roots)[root];
    if (t < rh->ray.tnear || t > rh->ray.tfar) continue;
    if (ctx->wasReported(hitKey(args->geomID, args->primID, root))) continue;
    const glm::dvec3 n = ctx->origin + t * ctx->direction - sphereCenter(s);
    rh->ray.tfar = float(t);
    rh->hit.Ng_x = float(n.x);
    rh->hit.Ng_y = float(n.y);
    rh->hit.Ng_z = float(n.z);
    rh->hit.u = float(root);
    rh->hit.v = 0;
    rh->hit.primID = args->primID;
    rh->hit.geomID = args->geomID;
    rh->hit.instID[0] = args->context->instID[0];
    return;
  }
}

void ExactSceneWalker::skipReported(const RTCFilterFunctionNArguments* args) {
  if (args->N != 1 || !args->valid[0]) return;
  const auto* ctx = reinterpret_cast<const WalkContext*>(args->context);
  const unsigned geometry = RTCHitN_geomID(args->hit, 1, 0);
  const unsigned primitive = RTCHitN_primID(args->hit, 1, 0);
  if (ctx->wasReported(hitKey(geometry, primitive, 0))) args->valid[0] = 0;
}

render::SceneEvent ExactSceneWalker::triangleEvent(uint32_t triangle, const glm::dvec3& o,
                                                   const glm::dvec3& d) const {
  const glm::dvec3& n = faceNormals_[triangle];
  const glm::dvec3 a = vertex(placed_.mesh, placed_.mesh.triangles[3 * triangle]);
  render::SceneEvent e;
  const double dn = glm::dot(d, n);
  e.t = dn != 0 ? glm::dot(a - o, n) / dn : HUGE_VAL;  // edge-on: no surface to report
  e.normal = n;
  e.material =
      placed_.mesh.triangleMaterials.empty() ? 0 : placed_.mesh.triangleMaterials[triangle];
  return e;
}

void ExactSceneWalker::walk(const render::Ray& ray, double tMin, double tMax,
                            const std::function<bool(const render::SceneEvent&)>& visit) const {
  auto [t0, t1] = render::intersectBox(ray.origin, ray.direction, box_.lo, box_.hi);
  t0 = std::max(t0, tMin);
  t1 = std::min(t1, tMax);
  if (!(t0 < t1)) return;
  WalkContext ctx;
  rtcInitIntersectContext(&ctx.rtc);
  ctx.walker = this;
  ctx.origin = ray.origin;
  ctx.direction = ray.direction;
  // Embree searches a little wider than [t0, t1] (its ray is the float rounding of ours); the
  // double distances decide what is reported.
  const float margin = float(epsilon_);
  float tNear = std::max(0.0f, float(t0) - margin);  // Embree asserts tnear >= 0
  const float tFar = float(t1) + margin;
  render::SceneEvent last;
  unsigned lastGeometry = RTC_INVALID_GEOMETRY_ID;
  for (;;) {
    RTCRayHit rh{};
    rh.ray.org_x = float(ray.origin.x);
    rh.ray.org_y = float(ray.origin.y);
    rh.ray.org_z = float(ray.origin.z);
    rh.ray.dir_x = float(ray.direction.x);
    rh.ray.dir_y = float(ray.direction.y);
    rh.ray.dir_z = float(ray.direction.z);
    rh.ray.tnear = tNear;
    rh.ray.tfar = tFar;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &ctx.rtc, &rh);
    const unsigned geometry = rh.hit.geomID;
    if (geometry == RTC_INVALID_GEOMETRY_ID) return;
    const unsigned root = geometry == sphereGeometry_ && rh.hit.u > 0.5f ? 1 : 0;
    ctx.reported.push_back(hitKey(geometry, rh.hit.primID, root));
    tNear = std::max(tNear, rh.ray.tfar - margin);
    render::SceneEvent e;
    if (geometry == meshGeometry_) {
      e = triangleEvent(rh.hit.primID, ray.origin, ray.direction);
    } else {
      const geometry::Sphere& s = placed_.spheres[rh.hit.primID];
      const auto roots = sphereRoots(ray.origin, ray.direction, sphereCenter(s), s.radius);
      if (!roots) continue;
      e.t = (*roots)[root];
      e.normal = glm::normalize(ray.origin + e.t * ray.direction - sphereCenter(s));
      e.material = s.material;
    }
    if (!(e.t >= t0 && e.t <= t1)) continue;
    // A ray through an edge or a vertex meets the neighbouring triangles of one surface at one
    // distance: that is one surface, as the voxel file stores one fragment there.
    if (geometry == meshGeometry_ && lastGeometry == meshGeometry_ &&
        std::abs(e.t - last.t) <= epsilon_ &&
        (glm::dot(e.normal, ray.direction) < 0) == (glm::dot(last.normal, ray.direction) < 0))
      continue;
    last = e;
    lastGeometry = geometry;
    if (!visit(e)) return;
  }
}

}  // namespace voxlink::exact
