// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/detail/viewer_state.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "format/validator.h"
#include "pack/open_file.h"
#include "tf/tf_presets.h"

namespace voxlink::viewer {

using render::kMaxBouncesLimit;
using render::Light;
using render::RenderSettings;
using render::Sampling;
using render::sceneLights;
using render::valueHistogram;
using render::gl::VoxLinkRenderer;
using tf::defaultTransferFunction;
using tf::displayRange;

Status ViewerState::load(const std::string& path, bool keepTf, VoxLinkRenderer* drawWith) {
  VOXLINK_ASSIGN_OR_RETURN(format::VoxLinkFile opened, pack::openValidatedFile(path));
  auto next = std::make_unique<format::VoxLinkFile>(std::move(opened));
  std::unique_ptr<VoxLinkRenderer> own;
  if (!drawWith) {
    VOXLINK_ASSIGN_OR_RETURN(own, VoxLinkRenderer::create(*next));
  }
  VOXLINK_ASSIGN_OR_RETURN(std::vector<Light> lights, render::sceneLights(next->metaJson()));
  file = std::move(next);
  ownRenderer = std::move(own);
  renderer = drawWith ? drawWith : ownRenderer.get();
  sceneLights = std::move(lights);
  settings.lights = settings.effects.any() ? sceneLights : std::vector<Light>{};
  if (!keepTf) tf = defaultTransferFunction(*file);
  classification = fileClassification(*file);
  removed = removedValues(classification);
  const auto& h = file->header();
  // Show the stored range and the TF's points, with a margin, so removed ranges are visible too.
  double lo = h.valueMin, hi = h.valueMax;
  for (const auto& p : tf.opacity) lo = std::min(lo, p.value), hi = std::max(hi, p.value);
  std::tie(lo, hi) = displayRange(lo, hi);
  const double margin = 0.1 * (hi - lo);
  editor.setView(lo - margin, hi + margin);
  histogram = valueHistogram(*file, lo - margin, hi + margin, 256);
  transferFunctionChanged();
  return Status::ok();
}

void ViewerState::transferFunctionChanged() {
  if (renderer) renderer->setTransferFunction(tf);
  if (file) visibleButRemoved = viewer::visibleButRemoved(tf, classification);
}

bool drawStatsPanel(ViewerState& s, const std::string& glDescription, uint32_t width,
                    uint32_t height) {
  const auto& h = s.file->header();
  ImGui::Text("%s", s.shownPath.empty() ? s.file->path().c_str() : s.shownPath.c_str());
  ImGui::Text("%ux%ux%u, brick %u, %llu voxels in %llu of %llu bricks", h.dims[0], h.dims[1],
              h.dims[2], h.brickSize, (unsigned long long)h.voxelCount,
              (unsigned long long)h.occupiedBrickCount,
              (unsigned long long)s.file->gridBrickCount());
  const auto& shading = s.settings.shading;
  const bool perVoxelShadows = shading.enabled && shading.shadows && !s.settings.effects.any() &&
                               shading.shadowRays == render::ShadowRays::kPerVoxel &&
                               !s.file->isScene();
  ImGui::Text("frame %.1f ms at %ux%u%s%s", s.lastRenderMs, width, height,
              s.lastFrameReduced ? " (reduced while moving)" : "",
              !perVoxelShadows           ? ""
              : s.lastFrameFilledShadows ? ", shadow cache filled"
                                         : ", shadow cache reused");
  ImGui::Text("GPU buffers %.2f MiB (sections, TF, gradient table)",
              s.renderer->gpuBytes() / 1048576.0);
  ImGui::TextDisabled("%s", glDescription.c_str());
  ImGui::TextDisabled(
      "drag: orbit | right/shift drag: pan | wheel, +/-: zoom | arrows | R reset | P screenshot | "
      "V sampling | H hide UI | Q quit");
  if (!s.message.empty()) ImGui::TextWrapped("%s", s.message.c_str());
  return false;
}

bool drawSettingsPanel(ViewerState& s) {
  bool changed = false;
  RenderSettings& r = s.settings;
  int sampling = r.sampling == Sampling::kVoxel ? 0 : 1;
  changed |= ImGui::RadioButton("voxel", &sampling, 0);
  ImGui::SameLine();
  changed |= ImGui::RadioButton("trilinear", &sampling, 1);
  r.sampling = sampling == 0 ? Sampling::kVoxel : Sampling::kTrilinear;
  if (r.sampling == Sampling::kTrilinear) {
    float step = float(r.stepVoxels);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120);
    if (ImGui::SliderFloat("step (voxels)", &step, 0.125f, 2.0f, "%.3f")) {
      r.stepVoxels = step;
      changed = true;
    }
  }
  changed |= ImGui::Checkbox("shading", &r.shading.enabled);
  ImGui::SameLine();
  changed |= ImGui::Checkbox("shadows", &r.shading.shadows);
  // The ray-traced mode (docs/effects.md): secondary rays, lit by the scene's lights.
  bool effects = false;
  effects |= ImGui::Checkbox("reflect", &r.effects.reflect);
  ImGui::SameLine();
  effects |= ImGui::Checkbox("refract", &r.effects.refract);
  ImGui::SameLine();
  effects |= ImGui::Checkbox("shadow rays", &r.effects.shadows);
  if (r.effects.any()) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(90);
    effects |= ImGui::SliderInt("bounces", &r.effects.maxBounces, 0, kMaxBouncesLimit);
  }
  if (effects) {
    r.lights = r.effects.any() ? s.sceneLights : std::vector<Light>{};
    if (r.effects.any() && r.sampling != Sampling::kVoxel) r.sampling = Sampling::kVoxel;
    changed = true;
  }
  float phong[4] = {float(r.shading.ambient), float(r.shading.diffuse), float(r.shading.specular),
                    float(r.shading.shininess)};
  ImGui::SetNextItemWidth(260);
  if (ImGui::DragFloat4("ka kd ks shininess", phong, 0.01f, 0.0f, 128.0f, "%.2f")) {
    r.shading.ambient = phong[0];
    r.shading.diffuse = phong[1];
    r.shading.specular = phong[2];
    r.shading.shininess = std::max(phong[3], 1.0f);
    changed = true;
  }
  float light[3] = {float(r.shading.lightDirection[0]), float(r.shading.lightDirection[1]),
                    float(r.shading.lightDirection[2])};
  ImGui::SetNextItemWidth(260);
  if (ImGui::DragFloat3("light (camera space)", light, 0.02f, -1.0f, 1.0f, "%.2f") &&
      light[0] * light[0] + light[1] * light[1] + light[2] * light[2] > 1e-6f) {
    r.shading.lightDirection = {light[0], light[1], light[2]};
    changed = true;
  }
  float bg[3] = {float(r.background[0]), float(r.background[1]), float(r.background[2])};
  if (ImGui::ColorEdit3("background", bg, ImGuiColorEditFlags_Float)) {
    r.background = {bg[0], bg[1], bg[2]};
    changed = true;
  }
  float scale = float(s.interactiveScale);
  ImGui::SetNextItemWidth(120);
  if (ImGui::SliderFloat("resolution while moving", &scale, 0.1f, 1.0f, "%.2f"))
    s.interactiveScale = scale;
  return changed;
}

bool drawTransferFunctionPanel(ViewerState& s) {
  const auto& h = s.file->header();
  const TfEditorContext context{&s.histogram, s.removed, h.valueMin, h.valueMax};
  bool changed = s.editor.draw(s.tf, context);
  if (changed) s.transferFunctionChanged();
  ImGui::Separator();
  ImGui::Text("pre-classification: %s", s.classification.description.c_str());
  if (!s.visibleButRemoved.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.55f, 0.3f, 1.0f));
    ImGui::TextWrapped(
        "The transfer function gives opacity to %s, which this file's pre-classification "
        "removed: those voxels cannot show.",
        tf::describeIntervals(s.visibleButRemoved).c_str());
    ImGui::PopStyleColor();
  }
  if (s.reclassifier.running()) {
    ImGui::ProgressBar(float(s.reclassifier.progress()), ImVec2(240, 0),
                       s.reclassifier.stage().c_str());
    ImGui::SameLine();
    if (ImGui::Button("cancel")) s.reclassifier.cancel();
  } else if (!s.visibleButRemoved.empty() && !s.shownPath.empty()) {
    // The renderer of a scene built in memory draws that build; a new file would lose it.
    ImGui::TextDisabled("re-classification: build the scene again (scene build) instead");
  } else if (!s.visibleButRemoved.empty()) {
    const std::string out = Reclassifier::outputPathFor(s.file->path());
    if (ImGui::Button("Re-classify from the source")) {
      Status started = s.reclassifier.start(*s.file, s.tf, out);
      s.message = started ? "re-classifying into " + out : started.message();
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "converts the source recorded in the file again, keeping what this TF shows,\n"
          "writes %s and reloads it",
          out.c_str());
  }
  return changed;
}

}  // namespace voxlink::viewer
