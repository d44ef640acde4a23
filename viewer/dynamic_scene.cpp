// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/dynamic_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "format/bricked_volume.h"
#include "scene/scene_animation.h"
#include "scene/scene_assembly.h"
#include "scene/scene_geometry.h"

namespace voxlink::viewer {

using render::gl::dynamicBrickBound;
using render::gl::DynamicSceneRenderer;
using render::gl::GlDynamicLayer;
namespace {

// The moving spheres' lists are per cell of 8^3 voxels whatever the file's bricks: for the
// moving 2XHE protein at 512x512 (docs/dynamic-scenes.md, "Moving sphere sets and particles")
// cells of 8 drew the frame fastest at grid 512 (median 132 ms against 175 with 4 and 298 with
// 2) and within the drift of 4 at 256 (128 against 119); per-voxel lists were 2x slower at 256.
constexpr uint32_t kSphereListCell = 8;

// The affine map p -> applyPose(pose, centre, M p) as a Transform.
scene::Transform posed(const scene::Pose& pose, const std::array<double, 3>& centre,
                       const scene::Transform& m) {
  auto map = [&](const std::array<double, 3>& p) {
    return scene::applyPose(pose, centre, m.apply(p));
  };
  const auto o = map({0, 0, 0});
  scene::Transform r;
  for (int c = 0; c < 3; ++c) {
    std::array<double, 3> unit{0, 0, 0};
    unit[size_t(c)] = 1;
    const auto p = map(unit);
    for (int row = 0; row < 3; ++row) r.m[size_t(row * 4 + c)] = p[size_t(row)] - o[size_t(row)];
  }
  for (int row = 0; row < 3; ++row) r.m[size_t(row * 4 + 3)] = o[size_t(row)];
  return r;
}

}  // namespace

DynamicScene::DynamicScene(scene::SceneDescription scene, format::VoxLinkFile file,
                           GlDynamicLayer layer)
    : scene_(std::move(scene)), file_(std::move(file)), layer_(std::move(layer)) {}

Result<DynamicScene::Prepared> DynamicScene::prepare(const scene::SceneDescription& scene,
                                                     const std::string& staticFile,
                                                     const scene::SceneProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  scene::SceneDescription still = scene;  // the static objects
  still.objects.clear();
  std::vector<size_t> movingObjects;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    if (scene.objects[i].animation)
      movingObjects.push_back(i);
    else
      still.objects.push_back(scene.objects[i]);
  }
  if (movingObjects.empty())
    return makeError(ErrorCode::kInvalidArgument, scene.path,
                     ": objects: no object has an \"animation\" (nothing moves)");
  if (still.objects.empty())
    return makeError(ErrorCode::kInvalidArgument, scene.path,
                     ": objects: a dynamic scene needs a static object besides the moving ones");
  // The grid of the whole scene at rest, kept while objects move.
  VOXLINK_ASSIGN_OR_RETURN(scene::PlacedScene all, scene::placeSceneGeometry(scene));
  still.grid.fitBounds = all.bounds;
  VOXLINK_ASSIGN_OR_RETURN(scene::SceneBuildOutput built, scene::buildScene(still, progress));
  VOXLINK_RETURN_IF_ERROR(format::writeBrickedVolume(staticFile, built.volume));
  VOXLINK_ASSIGN_OR_RETURN(format::VoxLinkFile file, format::VoxLinkFile::open(staticFile));
  geometry::VoxelGrid grid;
  for (int a = 0; a < 3; ++a) {
    grid.dims[size_t(a)] = file.header().dims[a];
    grid.origin[size_t(a)] = file.header().origin[a];
  }
  grid.spacing = file.header().spacing[0];
  if (file.header().spacing[1] != grid.spacing || file.header().spacing[2] != grid.spacing)
    return makeError(ErrorCode::kUnsupported, scene.path,
                     ": moving meshes need cubic voxels (the scene's volume has other spacings)");

  std::vector<Moving> moving;
  uint64_t bricks = 0, triangles = 0, spheres = 0, sphereReferences = 0;
  // The layer's bricks hold at most 8^3 voxels whatever the file's: its own brick map and pool
  // need not match the file's, and a 16^3 brick of 16-byte voxels, mostly empty around a
  // surface, is 64 KiB to zero per brick (the dragon at 512 needed 2862 of them, more than one
  // llvmpipe storage buffer of 128 MiB holds).
  const uint32_t brick = std::min(file.header().brickSize, 8u);
  for (size_t i : movingObjects) {
    const scene::SceneObject& o = scene.objects[i];
    scene::SceneDescription one = scene;
    one.objects = {o};
    VOXLINK_ASSIGN_OR_RETURN(scene::PlacedScene placed, scene::placeSceneGeometry(one));
    VOXLINK_RETURN_IF_ERROR(
        scene::checkAnimationInGrid(*o.animation, placed.bounds, grid, o.where));
    Moving m;
    m.object = i;
    m.restPositions.assign(placed.mesh.positions.begin(), placed.mesh.positions.end());
    m.triangles = placed.mesh.triangles;
    m.restBounds = placed.bounds;
    if (o.kind == scene::ObjectKind::kSphere || o.kind == scene::ObjectKind::kParticles) {
      // The file's spheres: the object placed with no transform and no radius scale.
      one.objects[0].transform = scene::Transform{};
      one.objects[0].radiusScale = 1;
      VOXLINK_ASSIGN_OR_RETURN(scene::PlacedScene raw, scene::placeSceneGeometry(one));
      m.isSpheres = true;
      m.fileSpheres = std::move(raw.spheres);
      // Per sphere the bricks its ball (a rigid pose keeps the radius) can touch anywhere.
      for (const geometry::Sphere& sp : placed.spheres) {
        const double e = 2 * sp.radius / grid.spacing + 0.02;  // gl_dynamic_spheres.cpp's margin
        sphereReferences += dynamicBrickBound({e, e, e}, kSphereListCell, grid.dims);
      }
      spheres += placed.spheres.size();
    }
    m.pose = samplePose(*o.animation, 0);
    std::array<double, 3> extent{};
    for (int a = 0; a < 3; ++a) {
      m.centre[size_t(a)] = 0.5 * (double(placed.bounds.min[a]) + placed.bounds.max[a]);
      extent[size_t(a)] = (double(placed.bounds.max[a]) - placed.bounds.min[a]) / grid.spacing;
    }
    if (o.animation->rotates()) {
      const double diameter =
          std::sqrt(extent[0] * extent[0] + extent[1] * extent[1] + extent[2] * extent[2]);
      extent.fill(diameter);
    }
    for (double& e : extent) e += 2;  // the conservative raster's touching voxels
    if (!m.isSpheres) bricks += dynamicBrickBound(extent, brick, grid.dims);
    triangles += placed.mesh.triangleCount();
    moving.push_back(std::move(m));
  }
  Prepared p;
  p.scene = scene;
  p.staticFile = staticFile;
  p.grid = grid;
  p.moving = std::move(moving);
  p.brick = brick;
  p.bricks = bricks;
  p.triangles = triangles;
  p.spheres = spheres;
  p.sphereReferences = sphereReferences;
  p.restBounds = all.bounds;
  p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return p;
}

Result<std::unique_ptr<DynamicScene>> DynamicScene::load(const scene::SceneDescription& scene,
                                                         const std::string& staticFile) {
  VOXLINK_ASSIGN_OR_RETURN(Prepared prepared, prepare(scene, staticFile));
  return load(std::move(prepared));
}

Result<std::unique_ptr<DynamicScene>> DynamicScene::load(Prepared p) {
  const auto start = std::chrono::steady_clock::now();
  VOXLINK_ASSIGN_OR_RETURN(format::VoxLinkFile file, format::VoxLinkFile::open(p.staticFile));
  VOXLINK_ASSIGN_OR_RETURN(
      GlDynamicLayer layer,
      GlDynamicLayer::create(p.grid.dims, p.brick, p.bricks, p.poolBufferBytes));
  const scene::SceneDescription& scene = p.scene;
  std::unique_ptr<DynamicScene> d(new DynamicScene(scene, std::move(file), std::move(layer)));
  d->grid_ = p.grid;
  d->moving_ = std::move(p.moving);
  if (p.spheres > 0) {
    VOXLINK_ASSIGN_OR_RETURN(
        render::gl::GlDynamicSpheres spheres,
        render::gl::GlDynamicSpheres::create(p.grid.dims, p.grid.origin, p.grid.spacing,
                                             kSphereListCell, p.sphereReferences));
    d->spheres_ = std::make_unique<render::gl::GlDynamicSpheres>(std::move(spheres));
  }
  uint32_t sphereCount = 0;
  for (Moving& m : d->moving_) {
    if (m.isSpheres) {  // its records' place in the sphere lists, fixed
      m.firstSphere = sphereCount;
      sphereCount += uint32_t(m.fileSpheres.size());
      continue;
    }
    const uint32_t base = uint32_t(d->gridPositions_.size() / 3);
    m.firstFloat = d->gridPositions_.size();
    m.firstIndex = d->triangles_.size();
    for (uint32_t t : m.triangles) d->triangles_.push_back(base + t);
    d->gridPositions_.resize(d->gridPositions_.size() + m.restPositions.size());
    // Materials: the moving object's scene material, whose index in every placement's table
    // is its place among the scene's materials (scene_geometry.h: scene materials first).
    const std::string& name = *scene.objects[m.object].material;
    uint32_t index = 0;
    while (index < scene.materials.size() && scene.materials[index].first != name) ++index;
    d->materials_.insert(d->materials_.end(), m.triangles.size() / 3, index);
  }
  VOXLINK_ASSIGN_OR_RETURN(d->renderer_,
                           DynamicSceneRenderer::create(d->file_, d->layer_, d->spheres_.get()));
  d->stats_.staticBuildSeconds =
      p.seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  d->stats_.movingTriangles = p.triangles;
  d->stats_.movingSpheres = p.spheres;
  d->stats_.layerBytes = d->layer_.gpuBytes() + (d->spheres_ ? d->spheres_->gpuBytes() : 0);
  d->restBounds_ = p.restBounds;
  return d;
}

Status DynamicScene::setTime(double seconds) {
  for (Moving& m : moving_) m.pose = samplePose(*scene_.objects[m.object].animation, seconds);
  return uploadPoses();
}

std::vector<DynamicScene::MovingObject> DynamicScene::movingObjects() const {
  std::vector<MovingObject> r;
  for (const Moving& m : moving_) r.push_back({m.object, m.restBounds});
  return r;
}

Status DynamicScene::setPose(size_t index, const scene::Pose& pose) {
  VOXLINK_RETURN_IF_ERROR(checkPose(index, pose));
  moving_[index].pose = pose;
  return uploadPoses();
}

Status DynamicScene::setPoses(const std::vector<scene::Pose>& poses) {
  if (poses.size() != moving_.size())
    return makeError(ErrorCode::kInvalidArgument, "dynamic scene: ", poses.size(), " poses for ",
                     moving_.size(), " moving objects");
  for (size_t i = 0; i < poses.size(); ++i) VOXLINK_RETURN_IF_ERROR(checkPose(i, poses[i]));
  for (size_t i = 0; i < poses.size(); ++i) moving_[i].pose = poses[i];
  return uploadPoses();
}

render::Box DynamicScene::posedBox(size_t index, const scene::Pose& pose) const {
  const Moving& m = moving_.at(index);
  render::Box r{glm::dvec3(1e300), glm::dvec3(-1e300)};
  for (int c = 0; c < 8; ++c) {
    const auto p = scene::applyPose(pose, m.centre,
                                    {(c & 1) ? m.restBounds.max[0] : m.restBounds.min[0],
                                     (c & 2) ? m.restBounds.max[1] : m.restBounds.min[1],
                                     (c & 4) ? m.restBounds.max[2] : m.restBounds.min[2]});
    for (int a = 0; a < 3; ++a) {
      r.lo[a] = std::min(r.lo[a], p[size_t(a)]);
      r.hi[a] = std::max(r.hi[a], p[size_t(a)]);
    }
  }
  return r;
}

Status DynamicScene::checkPose(size_t index, const scene::Pose& pose) const {
  if (index >= moving_.size())
    return makeError(ErrorCode::kInvalidArgument, "dynamic scene: moving object ", index,
                     " does not exist (", moving_.size(), " move)");
  const Moving& m = moving_[index];
  const std::string where = cat(scene_.path, ": objects[", m.object, "]");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(pose.translate[size_t(a)]) || !std::isfinite(pose.rotateDegrees[size_t(a)]))
      return makeError(ErrorCode::kInvalidArgument, where, ": a pose that is not finite");
  // The same rule as for keys (scene_animation.h): the rest bounds' corners, posed, in the grid;
  // up to a millionth of a voxel over: a guard for a translation clamped exactly to the grid's
  // face rounding past it (the test's clamp passes without it; the layer skips voxels outside).
  const geometry::Bounds3 box = scene::gridBox(grid_);
  const double slack = 1e-6 * grid_.spacing;
  const render::Box posed = posedBox(index, pose);
  for (int a = 0; a < 3; ++a)
    if (posed.lo[a] < box.min[a] - slack || posed.hi[a] > box.max[a] + slack)
      return makeError(ErrorCode::kInvalidArgument, where,
                       ": the pose moves the object outside the grid (", "xyz"[a], " ", posed.lo[a],
                       "..", posed.hi[a], " not in ", box.min[a], "..", box.max[a], ")");
  return Status::ok();
}

// Only what moved is re-voxelized: a mesh that kept its pose for two updates in a row goes into
// the layer's kept part (re-voxelized once more, alone, then saved), and later updates restore
// that part by a copy and re-voxelize the others on top, until a kept mesh moves. A mesh must
// stay still for two updates so that a drag that pauses for a frame does not rebuild the kept
// part twice. Integer sums do not depend on order: the layer is the full update's.
Status DynamicScene::uploadPoses() {
  std::vector<bool> still(moving_.size());
  bool keptStill = layer_.hasKept(), newlyStable = false;
  size_t meshCount = 0;
  std::vector<size_t> stable, others;
  for (size_t i = 0; i < moving_.size(); ++i) {
    const Moving& m = moving_[i];
    still[i] = m.uploaded && m.uploaded->translate == m.pose.translate &&
               m.uploaded->rotateDegrees == m.pose.rotateDegrees;
    if (m.isSpheres) continue;  // reMarkSpheres() below
    ++meshCount;
    if (m.kept && !still[i]) keptStill = false;
    const bool isStable = still[i] && m.unmovedUpdates >= 1;
    if (isStable && !m.kept) newlyStable = true;
    (isStable ? stable : others).push_back(i);
  }
  stats_.reVoxelizedTriangles = 0;
  if (meshCount == 0) {
    // No moving mesh: the layer stays as load() made it, empty.
  } else if (keptStill && !newlyStable) {  // the kept part as it is; the other meshes re-voxelized
    others.clear();
    for (size_t i = 0; i < moving_.size(); ++i)
      if (!moving_[i].isSpheres && !moving_[i].kept) others.push_back(i);
    VOXLINK_RETURN_IF_ERROR(reVoxelize(others, true));
  } else {
    layer_.forgetKept();
    for (Moving& m : moving_)
      if (!m.isSpheres) m.kept = false;
    if (!stable.empty()) {
      VOXLINK_RETURN_IF_ERROR(reVoxelize(stable, false));
      VOXLINK_RETURN_IF_ERROR(layer_.keep());
      for (size_t i : stable) moving_[i].kept = true;
    }
    VOXLINK_RETURN_IF_ERROR(reVoxelize(others, !stable.empty()));
  }
  VOXLINK_RETURN_IF_ERROR(reMarkSpheres(still));
  stats_.keptMeshes = stats_.keptSphereSets = 0;
  for (size_t i = 0; i < moving_.size(); ++i) {
    Moving& m = moving_[i];
    m.unmovedUpdates = still[i] ? m.unmovedUpdates + 1 : 0;
    m.uploaded = m.pose;
    (m.isSpheres ? stats_.keptSphereSets : stats_.keptMeshes) += m.kept ? 1 : 0;
  }
  stats_.layerBytes = layer_.gpuBytes() + (spheres_ ? spheres_->gpuBytes() : 0);
  return Status::ok();
}

// The meshes' rule for sphere sets: a set that stood for two updates goes into the lists' kept
// part (marked once more, alone, then saved); later updates restore it by a copy of the list
// heads and mark the other sets on top, until a kept set moves. Nothing moved: the lists stay.
Status DynamicScene::reMarkSpheres(const std::vector<bool>& still) {
  stats_.reVoxelizedSpheres = 0;
  stats_.reMarkedSphereSets = 0;
  if (!spheres_) return Status::ok();
  bool moved = false, keptStill = spheres_->hasKept(), newlyStable = false;
  std::vector<size_t> stable, others;
  for (size_t i = 0; i < moving_.size(); ++i) {
    const Moving& m = moving_[i];
    if (!m.isSpheres) continue;
    moved = moved || !still[i];
    if (m.kept && !still[i]) keptStill = false;
    const bool isStable = still[i] && m.unmovedUpdates >= 1;
    if (isStable && !m.kept) newlyStable = true;
    (isStable ? stable : others).push_back(i);
  }
  if (!moved) return Status::ok();
  auto markSets = [&](const std::vector<size_t>& sets) -> Status {
    for (size_t i : sets) {
      const std::vector<render::gl::DynamicSphere> placed = placedSpheres(i);
      VOXLINK_RETURN_IF_ERROR(spheres_->mark(moving_[i].firstSphere, placed));
      stats_.reVoxelizedSpheres += placed.size();
      ++stats_.reMarkedSphereSets;
    }
    return Status::ok();
  };
  if (keptStill && !newlyStable) {  // the kept sets restored, the others (all moved) marked
    spheres_->reset(true);
    return markSets(others);
  }
  spheres_->reset(false);  // forgets the kept part
  for (Moving& m : moving_)
    if (m.isSpheres) m.kept = false;
  if (!stable.empty()) {
    VOXLINK_RETURN_IF_ERROR(markSets(stable));
    VOXLINK_RETURN_IF_ERROR(spheres_->keep());
    for (size_t i : stable) moving_[i].kept = true;
  }
  return markSets(others);
}

std::vector<render::gl::DynamicSphere> DynamicScene::placedSpheres(size_t index) const {
  // As scene::placeSceneGeometry places the object frozen at this pose (frozenAt): the same
  // transform, applied in double to the file's spheres, then rounded to float.
  const Moving& m = moving_[index];
  const scene::SceneObject& o = scene_.objects[m.object];
  const scene::Transform t = posed(m.pose, m.centre, o.transform);
  const double scale = t.uniformScale();
  std::vector<render::gl::DynamicSphere> spheres;
  spheres.reserve(m.fileSpheres.size());
  for (const geometry::Sphere& s : m.fileSpheres) {
    const auto c = t.apply({s.center[0], s.center[1], s.center[2]});
    render::gl::DynamicSphere d;
    for (int a = 0; a < 3; ++a) d.centre[size_t(a)] = float(c[size_t(a)]);
    d.radius = float(s.radius * scale * o.radiusScale);
    d.material = s.material;
    spheres.push_back(d);
  }
  return spheres;
}

Status DynamicScene::checkLastUpdate() const {
  VOXLINK_RETURN_IF_ERROR(layer_.checkLastUpdate());
  return spheres_ ? spheres_->checkLastUpdate() : Status::ok();
}

Status DynamicScene::reVoxelize(const std::vector<size_t>& meshes, bool onKept) {
  for (size_t i : meshes) {
    const Moving& m = moving_[i];
    size_t out = m.firstFloat;
    for (size_t v = 0; v < m.restPositions.size(); v += 3) {
      const auto w = scene::applyPose(
          m.pose, m.centre, {m.restPositions[v], m.restPositions[v + 1], m.restPositions[v + 2]});
      const auto g = grid_.toGrid(w[0], w[1], w[2]);
      for (int a = 0; a < 3; ++a) gridPositions_[out++] = float(g[size_t(a)]);
    }
    stats_.reVoxelizedTriangles += m.triangles.size() / 3;
  }
  const size_t meshCount = size_t(
      std::count_if(moving_.begin(), moving_.end(), [](const Moving& m) { return !m.isSpheres; }));
  if (meshes.size() == meshCount)  // all of them: the concatenated arrays as they are
    return layer_.update(gridPositions_, triangles_, materials_, onKept);
  std::vector<float> positions;
  std::vector<uint32_t> triangles, materials;
  for (size_t i : meshes) {
    const Moving& m = moving_[i];
    const uint32_t base = uint32_t(positions.size() / 3);
    positions.insert(positions.end(), gridPositions_.begin() + ptrdiff_t(m.firstFloat),
                     gridPositions_.begin() + ptrdiff_t(m.firstFloat + m.restPositions.size()));
    for (uint32_t t : m.triangles) triangles.push_back(base + t);
    const size_t firstTriangle = m.firstIndex / 3;
    materials.insert(materials.end(), materials_.begin() + ptrdiff_t(firstTriangle),
                     materials_.begin() + ptrdiff_t(firstTriangle + m.triangles.size() / 3));
  }
  return layer_.update(positions, triangles, materials, onKept);
}

scene::SceneDescription DynamicScene::frozenAt(double seconds) const {
  scene::SceneDescription frozen = scene_;
  frozen.grid.fitBounds = restBounds_;
  for (const Moving& m : moving_) {
    scene::SceneObject& o = frozen.objects[m.object];
    o.transform = posed(samplePose(*o.animation, seconds), m.centre, o.transform);
    o.animation.reset();
  }
  return frozen;
}

}  // namespace voxlink::viewer
