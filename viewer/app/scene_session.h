// SPDX-License-Identifier: BSD-3-Clause
// A scene file (SCENE.json) in the viewer (docs/viewer.md, docs/dynamic-scenes.md). prepare()
// needs no GL and runs before the window opens: it reads the scene (the same one-line errors
// as `scene build`) and builds the static part, or the whole scene when nothing moves, into a
// scratch .vxl, which the viewer opens as it opens any file. attach() then makes the moving
// meshes' GPU layer and renderer (viewer/dynamic_scene.h) in the window's context. Per frame,
// update() places every moving mesh at the animation clock's time, or where the user dragged
// it, and re-voxelizes them when a pose changed. A static mesh can be made to move (promote():
// the static part rebuilt without it on a thread, then swapped in by update()).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/error.h"
#include "render/camera.h"
#include "scene/scene_assembly.h"
#include "viewer/app/detail/animation_clock.h"
#include "viewer/app/detail/mesh_promotion.h"
#include "viewer/app/detail/object_drag.h"
#include "viewer/dynamic_scene.h"

namespace voxlink::viewer {

struct SceneViewOptions {
  uint32_t resolution = 0;  // voxels along the longest axis; 0: the file's grid.resolution
  uint32_t brick = 0;       // 0: the file's grid.brick
};

class SceneSession {
 public:
  static Result<std::unique_ptr<SceneSession>> prepare(const std::string& scenePath,
                                                       const SceneViewOptions& options,
                                                       const scene::SceneProgress& progress = {});
  ~SceneSession();  // removes the scratch file
  SceneSession(const SceneSession&) = delete;
  SceneSession& operator=(const SceneSession&) = delete;

  const std::string& volumeFile() const { return volumeFile_; }
  bool moves() const { return prepared_.has_value() || dynamic_ != nullptr; }
  // Needs a current GL 4.5 context; once. Nothing to do for a scene that does not move.
  Status attach();
  // Frees the GPU layer and renderer while their context is still current (the viewer's window
  // goes before the session); the session draws nothing after it.
  void detach() { dynamic_.reset(); }
  // What draws the static part and the moving meshes; null when nothing moves.
  render::gl::VoxLinkRenderer* renderer() { return dynamic_ ? &dynamic_->renderer() : nullptr; }
  DynamicScene* dynamic() { return dynamic_.get(); }

  AnimationClock& clock() { return clock_; }
  // Sets the clock's time (the panel's slider); the next update() places the meshes there.
  void setTime(double seconds);
  // Advances the clock by `dtSeconds` and re-voxelizes the moving meshes if a pose changed.
  // Returns whether it did (the image must be drawn again).
  Result<bool> update(double dtSeconds);

  // The moving meshes, in DynamicScene::movingObjects() order.
  size_t movingCount() const;
  std::string movingName(size_t index) const;  // "objects[2] dragon.ply"
  // A held object stays where it was dragged instead of following its animation.
  bool held(size_t index) const { return held_.at(index).has_value(); }
  void release(size_t index);
  // The moving meshes' world boxes at their current poses (for picking), and the grid's box.
  std::vector<render::Box> movingBoxes() const;
  render::Box gridBox() const;

  // A drag of moving mesh `index`: from its current pose, by the cursor's motion since the drag
  // began; the object is held from then on. The clamp of the last dragTo is kept for the panel.
  Status beginDrag(size_t index);
  Result<DraggedPose> dragTo(const render::Camera& camera, double dxPixels, double dyPixels,
                             double viewportHeight);
  void endDrag() { drag_.reset(); }
  std::optional<size_t> dragging() const {
    return drag_ ? std::optional<size_t>(drag_->index) : std::nullopt;
  }
  const std::array<bool, 3>& lastClamp() const { return lastClamp_; }

  // Static meshes that can be made to move (a scene material), and their boxes at rest.
  const std::vector<StaticObject>& staticObjects() const { return staticObjects_; }
  std::vector<render::Box> staticBoxes() const;
  std::string objectName(size_t object) const;  // "objects[2] dragon.ply"
  // Starts making objects[object] move: its static part is rebuilt without it on a thread; a
  // later update() (in the GL context) swaps the new scene in, with the mesh held at rest and
  // the other meshes' held poses kept. Errors: withObjectMoving's, a promotion under way.
  Status promote(size_t object);
  // The object being promoted and the rebuild's progress (0..1), if any.
  std::optional<std::pair<size_t, double>> promoting() const;
  // Blocks until a promotion under way is swapped in (tests; update() does not wait).
  Status finishPromotion() { return applyPromotion(true); }
  // True once after a promotion was swapped in: the viewer reopens volumeFile() with renderer().
  bool takeRebuilt() { return std::exchange(rebuilt_, false); }
  // The moving mesh index of a scene object, if it moves.
  std::optional<size_t> movingIndexOf(size_t object) const;

 private:
  SceneSession(std::string volumeFile, double span);
  scene::Pose currentPose(size_t index) const;
  Status applyPromotion(bool wait);
  struct Drag {
    size_t index = 0;
    scene::Pose start;
    render::Box startBox;
  };
  std::string volumeFile_;
  std::optional<DynamicScene::Prepared> prepared_;  // until attach()
  std::unique_ptr<DynamicScene> dynamic_;
  AnimationClock clock_;
  std::vector<std::optional<scene::Pose>> held_;
  std::optional<Drag> drag_;
  std::array<bool, 3> lastClamp_{};
  bool posesChanged_ = true;             // the first update() places the meshes
  scene::SceneDescription description_;  // with the overrides and the promotions so far
  std::vector<StaticObject> staticObjects_;
  std::unique_ptr<BackgroundPrepare> promotion_;
  bool rebuilt_ = false;
};

}  // namespace voxlink::viewer
