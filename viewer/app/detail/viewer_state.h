// SPDX-License-Identifier: BSD-3-Clause
// What the viewer holds between frames: the open file and its renderer, the transfer function
// and what the file's classification says about it, and the panels that edit them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "format/voxlink_file.h"
#include "render/gl/voxlink_renderer.h"
#include "render/value_histogram.h"
#include "viewer/app/detail/classification_check.h"
#include "viewer/app/detail/reclassifier.h"
#include "viewer/app/detail/tf_editor.h"

namespace voxlink::viewer {

using render::Light;
using render::RenderSettings;
using render::sceneLights;
using render::ValueHistogram;
using render::gl::VoxLinkRenderer;

struct ViewerState {
  std::unique_ptr<format::VoxLinkFile> file;
  // What draws: the file's own renderer, or a scene session's (moving meshes included).
  VoxLinkRenderer* renderer = nullptr;
  std::unique_ptr<VoxLinkRenderer> ownRenderer;
  tf::TransferFunction tf;
  FileClassification classification;
  std::vector<tf::ValueInterval> removed;            // what the file does not hold
  std::vector<tf::ValueInterval> visibleButRemoved;  // what the TF asks for in vain
  ValueHistogram histogram;
  TfEditor editor;
  Reclassifier reclassifier;
  RenderSettings settings;
  std::vector<Light> sceneLights;  // the file's lights (META), used when effects are on
  double interactiveScale = 0.5;   // resolution factor while the user drags
  double lastRenderMs = 0;
  bool lastFrameReduced = false;
  // Per-voxel shadow rays: whether the last frame filled the cache (a turn, a new TF) or read
  // the codes as they were (a still frame, a zoom, a pan; docs/shadows.md).
  bool lastFrameFilledShadows = false;
  std::string message;    // last screenshot / reload / error line
  std::string shownPath;  // the scene file a scratch .vxl was built from (else empty)

  // Opens `path` and builds its renderer (GL context current); keeps the TF when `keepTf`.
  // With `drawWith` (a renderer over the same file, owned by the caller) it draws with that.
  Status load(const std::string& path, bool keepTf, VoxLinkRenderer* drawWith = nullptr);
  // After the TF changed: uploads it and re-checks it against the classification.
  void transferFunctionChanged();
};

// The ImGui panels; each returns true when the image must be rendered again.
bool drawStatsPanel(ViewerState& state, const std::string& glDescription, uint32_t width,
                    uint32_t height);
bool drawSettingsPanel(ViewerState& state);
bool drawTransferFunctionPanel(ViewerState& state);

}  // namespace voxlink::viewer
