// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app/detail/tf_editor.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "render/image.h"
#include "tf/tf_presets.h"

namespace voxlink::viewer {

using render::srgbEncode;
using render::ValueHistogram;
using tf::importParaViewPreset;
using tf::tfPreset;
using tf::tfPresetNames;

namespace {

constexpr float kPointRadius = 5.0f;

ImU32 toImColor(const std::array<double, 3>& rgb, int alpha = 255) {
  auto c = [](double v) { return int(std::lround(255.0 * srgbEncode(v))); };
  return IM_COL32(c(rgb[0]), c(rgb[1]), c(rgb[2]), alpha);
}

// Keeps point i between its neighbours so the list stays sorted.
template <class Point>
double clampBetween(const std::vector<Point>& points, int i, double v) {
  if (i > 0) v = std::max(v, points[i - 1].value);
  if (i + 1 < int(points.size())) v = std::min(v, points[i + 1].value);
  return v;
}

// A strip of the editor showing the values [lo, hi] across its width: an invisible button (the
// last ImGui item) that takes the mouse, and the mapping between values and screen x.
struct ValueStrip {
  ImVec2 origin, size;
  double lo, hi;

  ValueStrip(const char* id, float height, double viewLo, double viewHi)
      : origin(ImGui::GetCursorScreenPos()),
        size(std::max(ImGui::GetContentRegionAvail().x, 100.0f), height),
        lo(viewLo),
        hi(viewHi) {
    ImGui::InvisibleButton(id, size,
                           ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  }
  float xOf(double v) const { return origin.x + float((v - lo) / (hi - lo)) * size.x; }
  double valueOf(float x) const { return lo + double(x - origin.x) / size.x * (hi - lo); }
};

// The mouse edits of a strip's points, the same for opacity and colour points: a left click on
// the hovered point selects it (and unselects the other kind's point, `otherSelected`) and
// drags it while held (`dragTo(i)` moves point i to the mouse, true when it moved); a double
// click off the points inserts `newPoint()` in value order; a right click removes the hovered
// point, never the last one. True when the points changed.
template <class Point, class DragTo, class NewPoint>
bool editPoints(std::vector<Point>& pts, int hovered, int& selected, int& dragging,
                int& otherSelected, DragTo dragTo, NewPoint newPoint) {
  bool changed = false;
  if (ImGui::IsItemActivated() && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && hovered >= 0) {
    dragging = selected = hovered;
    otherSelected = -1;
  }
  if (dragging >= 0 && ImGui::IsMouseDown(ImGuiMouseButton_Left))
    changed = dragTo(dragging);
  else
    dragging = -1;
  if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && hovered < 0) {
    const Point p = newPoint();
    auto at = std::upper_bound(pts.begin(), pts.end(), p.value,
                               [](double v, const Point& q) { return v < q.value; });
    selected = int(pts.insert(at, p) - pts.begin());
    changed = true;
  }
  if (ImGui::IsItemHovered() && ImGui::IsMouseClicked(ImGuiMouseButton_Right) && hovered >= 0 &&
      pts.size() > 1) {
    pts.erase(pts.begin() + hovered);
    selected = -1;
    changed = true;
  }
  return changed;
}

}  // namespace

bool TfEditor::draw(tf::TransferFunction& tf, const TfEditorContext& context) {
  bool changed = false;
  ImGui::PushID(this);
  float alphaMax = alphaMax_;
  ImGui::SetNextItemWidth(120);
  if (ImGui::SliderFloat("opacity axis", &alphaMax, 0.02f, 1.0f, "%.2f",
                         ImGuiSliderFlags_Logarithmic))
    alphaMax_ = alphaMax;
  ImGui::SameLine();
  double lo = viewLo_, hi = viewHi_;
  ImGui::SetNextItemWidth(200);
  if (ImGui::InputDouble("##lo", &lo, 0, 0, "%.4g")) viewLo_ = std::min(lo, viewHi_ - 1e-9);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(200);
  if (ImGui::InputDouble("value range##hi", &hi, 0, 0, "%.4g"))
    viewHi_ = std::max(hi, viewLo_ + 1e-9);
  changed |= drawOpacity(tf, context);
  changed |= drawColorBar(tf);
  changed |= drawSelection(tf);
  changed |= drawFiles(tf, context);
  ImGui::PopID();
  return changed;
}

bool TfEditor::drawOpacity(tf::TransferFunction& tf, const TfEditorContext& context) {
  const ValueStrip strip("opacity", 150.0f, viewLo_, viewHi_);
  const ImVec2 origin = strip.origin, size = strip.size;
  ImDrawList* draw = ImGui::GetWindowDrawList();
  auto yOf = [&](double a) { return origin.y + size.y - float(a / alphaMax_) * size.y; };
  auto alphaOf = [&](float y) {
    return std::clamp(double(origin.y + size.y - y) / size.y * alphaMax_, 0.0, 1.0);
  };
  draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y),
                      IM_COL32(30, 30, 34, 255));

  // Histogram of the stored values, log scale.
  if (const ValueHistogram* h = context.histogram; h && h->maxCount > 0) {
    const double norm = std::log1p(double(h->maxCount));
    const double width = (h->hi - h->lo) / h->counts.size();
    for (size_t i = 0; i < h->counts.size(); ++i) {
      if (!h->counts[i]) continue;
      const float x0 = strip.xOf(h->lo + i * width),
                  x1 = std::max(strip.xOf(h->lo + (i + 1) * width), x0 + 1.0f);
      const float top = origin.y + size.y - float(std::log1p(double(h->counts[i])) / norm) * size.y;
      draw->AddRectFilled(ImVec2(x0, top), ImVec2(x1, origin.y + size.y),
                          IM_COL32(90, 90, 100, 255));
    }
  }
  // Values the pre-classification removed: the file holds none of them.
  for (const auto& r : context.removed) {
    const float x0 = std::max(strip.xOf(r.lo), origin.x),
                x1 = std::min(strip.xOf(r.hi), origin.x + size.x);
    if (x1 > x0)
      draw->AddRectFilled(ImVec2(x0, origin.y), ImVec2(x1, origin.y + size.y),
                          IM_COL32(200, 50, 50, 55));
  }
  // The opacity polyline, constant beyond the end points.
  auto& pts = tf.opacity;
  std::vector<ImVec2> line;
  line.emplace_back(origin.x, yOf(pts.front().alpha));
  for (const auto& p : pts) line.emplace_back(strip.xOf(p.value), yOf(p.alpha));
  line.emplace_back(origin.x + size.x, yOf(pts.back().alpha));
  draw->PushClipRect(origin, ImVec2(origin.x + size.x, origin.y + size.y), true);
  draw->AddPolyline(line.data(), int(line.size()), IM_COL32(240, 240, 240, 255), 0, 2.0f);
  int hovered = -1;
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  for (int i = 0; i < int(pts.size()); ++i) {
    const ImVec2 c(strip.xOf(pts[i].value), yOf(pts[i].alpha));
    const float dx = mouse.x - c.x, dy = mouse.y - c.y;
    if (dx * dx + dy * dy < 2.5f * kPointRadius * kPointRadius) hovered = i;
    draw->AddCircleFilled(
        c, kPointRadius,
        i == selectedOpacity_ ? IM_COL32(255, 200, 40, 255) : IM_COL32(255, 255, 255, 255));
  }
  draw->PopClipRect();

  const bool changed = editPoints(
      pts, hovered, selectedOpacity_, draggingOpacity_, selectedColor_,
      [&](int i) {
        auto& p = pts[i];
        const tf::OpacityPoint moved{clampBetween(pts, i, strip.valueOf(mouse.x)),
                                     alphaOf(mouse.y)};
        const bool moves = moved.value != p.value || moved.alpha != p.alpha;
        p = moved;
        return moves;
      },
      [&] {
        return tf::OpacityPoint{strip.valueOf(mouse.x), alphaOf(mouse.y)};
      });
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "value %.4g, opacity %.3f\ndrag a point, double-click to add, right-click to remove",
        strip.valueOf(mouse.x), alphaOf(mouse.y));
  return changed;
}

bool TfEditor::drawColorBar(tf::TransferFunction& tf) {
  const ValueStrip strip("colors", 22.0f, viewLo_, viewHi_);
  const ImVec2 origin = strip.origin, size = strip.size;
  ImDrawList* draw = ImGui::GetWindowDrawList();
  constexpr int kSegments = 128;
  for (int i = 0; i < kSegments; ++i) {
    const float x0 = origin.x + size.x * i / kSegments,
                x1 = origin.x + size.x * (i + 1) / kSegments;
    draw->AddRectFilled(ImVec2(x0, origin.y), ImVec2(x1 + 1, origin.y + size.y - 8),
                        toImColor(tf.colorAt(strip.valueOf(0.5f * (x0 + x1)))));
  }
  auto& pts = tf.color;
  int hovered = -1;
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  for (int i = 0; i < int(pts.size()); ++i) {
    const float x = strip.xOf(pts[i].value), y = origin.y + size.y - 8;
    if (std::abs(mouse.x - x) < kPointRadius && mouse.y >= origin.y && mouse.y <= origin.y + size.y)
      hovered = i;
    draw->AddTriangleFilled(
        ImVec2(x, y), ImVec2(x - 5, y + 8), ImVec2(x + 5, y + 8),
        i == selectedColor_ ? IM_COL32(255, 200, 40, 255) : IM_COL32(230, 230, 230, 255));
  }
  return editPoints(
      pts, hovered, selectedColor_, draggingColor_, selectedOpacity_,
      [&](int i) {
        const double v = clampBetween(pts, i, strip.valueOf(mouse.x));
        const bool moves = v != pts[i].value;
        pts[i].value = v;
        return moves;
      },
      [&] {
        const double v = strip.valueOf(mouse.x);
        return tf::ColorPoint{v, tf.colorAt(v)};
      });
}

bool TfEditor::drawSelection(tf::TransferFunction& tf) {
  bool changed = false;
  if (selectedOpacity_ >= int(tf.opacity.size())) selectedOpacity_ = -1;
  if (selectedColor_ >= int(tf.color.size())) selectedColor_ = -1;
  if (selectedOpacity_ >= 0) {
    auto& p = tf.opacity[selectedOpacity_];
    double v = p.value, a = p.alpha;
    ImGui::SetNextItemWidth(150);
    if (ImGui::InputDouble("value##op", &v, 0, 0, "%.6g")) {
      p.value = clampBetween(tf.opacity, selectedOpacity_, v);
      changed = true;
    }
    ImGui::SameLine();
    ImGui::SetNextItemWidth(150);
    if (ImGui::InputDouble("opacity per unit length", &a, 0.001, 0.01, "%.4f")) {
      p.alpha = std::clamp(a, 0.0, 1.0);
      changed = true;
    }
  } else if (selectedColor_ >= 0) {
    auto& p = tf.color[selectedColor_];
    double v = p.value;
    ImGui::SetNextItemWidth(150);
    if (ImGui::InputDouble("value##col", &v, 0, 0, "%.6g")) {
      p.value = clampBetween(tf.color, selectedColor_, v);
      changed = true;
    }
    ImGui::SameLine();
    float rgb[3] = {float(p.rgb[0]), float(p.rgb[1]), float(p.rgb[2])};
    if (ImGui::ColorEdit3("colour (linear)", rgb, ImGuiColorEditFlags_Float)) {
      for (int c = 0; c < 3; ++c) p.rgb[c] = std::clamp(double(rgb[c]), 0.0, 1.0);
      changed = true;
    }
  } else {
    ImGui::TextDisabled("select a point to edit it exactly");
  }
  return changed;
}

bool TfEditor::drawFiles(tf::TransferFunction& tf, const TfEditorContext& context) {
  bool changed = false;
  ImGui::SetNextItemWidth(160);
  if (ImGui::BeginCombo("preset", tf.name.empty() ? "(custom)" : tf.name.c_str())) {
    for (const std::string& name : tfPresetNames())
      if (ImGui::Selectable(name.c_str())) {
        auto preset =
            tfPreset(name, context.valueMin,
                     context.valueMax > context.valueMin ? context.valueMax : context.valueMin + 1);
        if (preset) {
          tf = *preset;
          changed = true;
        }
      }
    ImGui::EndCombo();
  }
  ImGui::SetNextItemWidth(300);
  ImGui::InputText("file", path_, sizeof path_);
  if (ImGui::Button("Load TF")) {
    auto loaded = tf::loadTransferFunction(path_);
    message_ = loaded ? std::string("loaded ") + path_ : loaded.message();
    if (loaded) {
      tf = *loaded;
      changed = true;
    }
  }
  ImGui::SameLine();
  if (ImGui::Button("Save TF")) {
    Status s = tf::saveTransferFunction(tf, path_);
    message_ = s ? std::string("saved ") + path_ : s.message();
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(140);
  ImGui::InputTextWithHint("##pvname", "ParaView preset name", paraviewName_, sizeof paraviewName_);
  ImGui::SameLine();
  if (ImGui::Button("Import ParaView")) {
    auto imported =
        importParaViewPreset(path_, {paraviewName_, context.valueMin, context.valueMax});
    message_ = imported ? "imported '" + imported->name + "' from " + path_ : imported.message();
    if (imported) {
      tf = *imported;
      changed = true;
    }
  }
  if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
  if (changed) selectedOpacity_ = selectedColor_ = -1;
  return changed;
}

}  // namespace voxlink::viewer
