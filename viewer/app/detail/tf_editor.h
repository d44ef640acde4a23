// SPDX-License-Identifier: BSD-3-Clause
// The transfer function editor (Dear ImGui): opacity points over a histogram of the stored
// values, a colour bar with colour points, the value ranges the file's pre-classification
// removed shaded, presets, and load/save of TF JSON and ParaView colour-map presets.
#pragma once

#include <string>
#include <vector>

#include "render/value_histogram.h"
#include "tf/transfer_function.h"
#include "tf/value_interval.h"

namespace voxlink::viewer {

using render::ValueHistogram;

struct TfEditorContext {
  const ValueHistogram* histogram = nullptr;
  std::vector<tf::ValueInterval> removed;  // values the file does not hold
  double valueMin = 0, valueMax = 1;       // stored range, for presets
};

class TfEditor {
 public:
  // Draws into the current ImGui window; true when `tf` changed.
  bool draw(tf::TransferFunction& tf, const TfEditorContext& context);
  // The value range the editor shows; the app sets it once from the file.
  void setView(double lo, double hi) {
    viewLo_ = lo;
    viewHi_ = hi;
  }

 private:
  bool drawOpacity(tf::TransferFunction& tf, const TfEditorContext& context);
  bool drawColorBar(tf::TransferFunction& tf);
  bool drawSelection(tf::TransferFunction& tf);
  bool drawFiles(tf::TransferFunction& tf, const TfEditorContext& context);

  double viewLo_ = 0, viewHi_ = 1;
  float alphaMax_ = 1.0f;
  int selectedOpacity_ = -1, selectedColor_ = -1;
  int draggingOpacity_ = -1, draggingColor_ = -1;
  char path_[512] = "transfer_function.json";
  char paraviewName_[128] = "";
  std::string message_;
};

}  // namespace voxlink::viewer
