// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/scene_session.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>

#include "format/bricked_volume.h"
#include "scene/scene_animation.h"

namespace voxlink::viewer {
namespace {

// A scratch path per session, unique in the process and among processes.
std::string scratchPath() {
  static std::atomic<int> next{0};
  return (std::filesystem::temp_directory_path() /
          cat("voxlink-view-", getpid(), "-", next++, ".vxl"))
      .string();
}

render::Box toBox(const geometry::Bounds3& b) {
  return {glm::dvec3(b.min[0], b.min[1], b.min[2]), glm::dvec3(b.max[0], b.max[1], b.max[2])};
}

// An object's file name, or "sphere" for a sphere given in the scene file (it has no file).
std::string objectLabel(const scene::SceneObject& o) {
  if (o.kind == scene::ObjectKind::kSphere) return "sphere";
  return std::filesystem::path(o.path).filename().string();
}

}  // namespace

SceneSession::SceneSession(std::string volumeFile, double span)
    : volumeFile_(std::move(volumeFile)), clock_(span) {}

SceneSession::~SceneSession() {
  std::error_code ignored;
  if (promotion_) {  // a rebuild under way: its scratch file goes too
    promotion_->take(true);
    std::filesystem::remove(promotion_->staticFile(), ignored);
  }
  std::filesystem::remove(volumeFile_, ignored);
}

Result<std::unique_ptr<SceneSession>> SceneSession::prepare(const std::string& scenePath,
                                                            const SceneViewOptions& options,
                                                            const scene::SceneProgress& progress) {
  VOXLINK_ASSIGN_OR_RETURN(scene::SceneDescription description,
                           scene::readSceneDescription(scenePath));
  if (options.resolution) description.grid.resolution = options.resolution;
  if (options.brick) description.grid.brickSize = options.brick;
  std::unique_ptr<SceneSession> s(new SceneSession(scratchPath(), description.animationSpan()));
  s->description_ = description;
  VOXLINK_ASSIGN_OR_RETURN(s->staticObjects_, movableStaticObjects(description));
  bool moves = false;
  for (const scene::SceneObject& o : description.objects) moves |= o.animation.has_value();
  if (moves) {
    VOXLINK_ASSIGN_OR_RETURN(DynamicScene::Prepared prepared,
                             DynamicScene::prepare(description, s->volumeFile_, progress));
    s->held_.resize(prepared.moving.size());
    s->prepared_ = std::move(prepared);
  } else {  // what `scene build` writes
    VOXLINK_ASSIGN_OR_RETURN(scene::SceneBuildOutput built,
                             scene::buildScene(description, progress));
    VOXLINK_RETURN_IF_ERROR(format::writeBrickedVolume(s->volumeFile_, built.volume));
  }
  return s;
}

Status SceneSession::attach() {
  if (!prepared_) return Status::ok();
  VOXLINK_ASSIGN_OR_RETURN(dynamic_, DynamicScene::load(std::move(*prepared_)));
  prepared_.reset();
  posesChanged_ = true;
  return Status::ok();
}

void SceneSession::setTime(double seconds) {
  clock_.setTime(seconds);
  posesChanged_ = true;
}

scene::Pose SceneSession::currentPose(size_t index) const {
  if (held_[index]) return *held_[index];
  const size_t object = dynamic_->movingObjects()[index].object;
  return scene::samplePose(*dynamic_->description().objects[object].animation, clock_.time());
}

Result<bool> SceneSession::update(double dtSeconds) {
  VOXLINK_RETURN_IF_ERROR(applyPromotion(false));
  if (!dynamic_) return false;
  bool follows = false;  // some mesh follows its animation
  for (const auto& h : held_) follows |= !h.has_value();
  if (clock_.advance(dtSeconds) && follows) posesChanged_ = true;
  if (!posesChanged_) return false;
  std::vector<scene::Pose> poses(held_.size());
  for (size_t i = 0; i < poses.size(); ++i) poses[i] = currentPose(i);
  posesChanged_ = false;
  VOXLINK_RETURN_IF_ERROR(dynamic_->setPoses(poses));
  return true;
}

std::vector<render::Box> SceneSession::staticBoxes() const {
  std::vector<render::Box> boxes;
  for (const StaticObject& m : staticObjects_) boxes.push_back(toBox(m.restBounds));
  return boxes;
}

std::string SceneSession::objectName(size_t object) const {
  return cat("objects[", object, "] ", objectLabel(description_.objects.at(object)));
}

std::optional<size_t> SceneSession::movingIndexOf(size_t object) const {
  if (!dynamic_) return std::nullopt;
  const auto objects = dynamic_->movingObjects();
  for (size_t i = 0; i < objects.size(); ++i)
    if (objects[i].object == object) return i;
  return std::nullopt;
}

Status SceneSession::promote(size_t object) {
  if (promotion_)
    return makeError(ErrorCode::kInvalidArgument, description_.path, ": objects[",
                     promotion_->object(), "] is being made to move; one at a time");
  if (prepared_)
    return makeError(ErrorCode::kInvalidArgument, "promote: the session is not attached yet");
  VOXLINK_ASSIGN_OR_RETURN(scene::SceneDescription moved, withObjectMoving(description_, object));
  promotion_ = std::make_unique<BackgroundPrepare>(std::move(moved), scratchPath(), object);
  return Status::ok();
}

std::optional<std::pair<size_t, double>> SceneSession::promoting() const {
  if (!promotion_) return std::nullopt;
  return std::pair{promotion_->object(), promotion_->progress()};
}

// Swaps the promoted scene in: its GPU layer made here (the GL context), every moving mesh held
// where it was (the promoted one at rest), the old scratch file removed.
Status SceneSession::applyPromotion(bool wait) {
  if (!promotion_) return Status::ok();
  auto done = promotion_->take(wait);
  if (!done) return Status::ok();
  const std::unique_ptr<BackgroundPrepare> job = std::move(promotion_);
  std::error_code ignored;
  if (!*done) {
    std::filesystem::remove(job->staticFile(), ignored);
    return done->error();
  }
  auto next = DynamicScene::load(std::move(**done));
  if (!next) {
    std::filesystem::remove(job->staticFile(), ignored);
    return next.error();
  }
  const auto objects = (*next)->movingObjects();
  std::vector<std::optional<scene::Pose>> held(objects.size());
  for (size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].object == job->object()) {
      held[i] = scene::Pose{};
    } else if (const auto before = movingIndexOf(objects[i].object)) {
      held[i] = held_[*before];
    }
  }
  drag_.reset();
  dynamic_ = std::move(*next);
  held_ = std::move(held);
  std::filesystem::remove(volumeFile_, ignored);
  volumeFile_ = job->staticFile();
  description_ = dynamic_->description();
  staticObjects_.erase(
      std::remove_if(staticObjects_.begin(), staticObjects_.end(),
                     [&](const StaticObject& m) { return m.object == job->object(); }),
      staticObjects_.end());
  posesChanged_ = true;
  rebuilt_ = true;
  return Status::ok();
}

size_t SceneSession::movingCount() const { return held_.size(); }

std::string SceneSession::movingName(size_t index) const {
  if (!moves()) return {};
  const auto& objects = dynamic_ ? dynamic_->description().objects : prepared_->scene.objects;
  const size_t object =
      dynamic_ ? dynamic_->movingObjects().at(index).object : prepared_->moving.at(index).object;
  return cat("objects[", object, "] ", objectLabel(objects[object]));
}

void SceneSession::release(size_t index) {
  held_.at(index).reset();
  if (drag_ && drag_->index == index) drag_.reset();
  posesChanged_ = true;
}

std::vector<render::Box> SceneSession::movingBoxes() const {
  std::vector<render::Box> boxes;
  if (!dynamic_) return boxes;
  for (size_t i = 0; i < held_.size(); ++i) boxes.push_back(dynamic_->posedBox(i, currentPose(i)));
  return boxes;
}

render::Box SceneSession::gridBox() const {
  return dynamic_ ? toBox(scene::gridBox(dynamic_->grid())) : render::Box{};
}

Status SceneSession::beginDrag(size_t index) {
  if (!dynamic_ || index >= held_.size())
    return makeError(ErrorCode::kInvalidArgument, "drag: moving object ", index,
                     " does not exist (", held_.size(), " move)");
  const scene::Pose start = currentPose(index);
  drag_ = Drag{index, start, dynamic_->posedBox(index, start)};
  held_[index] = start;
  lastClamp_ = {};
  return Status::ok();
}

Result<DraggedPose> SceneSession::dragTo(const render::Camera& camera, double dxPixels,
                                         double dyPixels, double viewportHeight) {
  if (!drag_) return makeError(ErrorCode::kInvalidArgument, "drag: no object is being dragged");
  VOXLINK_ASSIGN_OR_RETURN(DraggedPose dragged,
                           dragPose(camera, drag_->start, drag_->startBox, gridBox(), dxPixels,
                                    dyPixels, viewportHeight));
  held_[drag_->index] = dragged.pose;
  lastClamp_ = dragged.clamped;
  posesChanged_ = true;
  return dragged;
}

}  // namespace voxlink::viewer
