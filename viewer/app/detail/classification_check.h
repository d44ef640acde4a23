// SPDX-License-Identifier: BSD-3-Clause
// What a file's pre-classification removed, and whether a transfer function asks for any of it
// (paper, section 5.1: removed voxels cannot be shown without re-classifying the source).
#pragma once

#include <string>
#include <vector>

#include "format/voxlink_file.h"
#include "tf/transfer_function.h"
#include "tf/value_interval.h"

namespace voxlink::viewer {

struct FileClassification {
  bool recorded = false;                // META holds a classification
  std::vector<tf::ValueInterval> keep;  // source units, merged, ascending
  std::string description;
};

// From META (convert::classificationFromJson); standardized keep-outside intervals are mapped
// back to source units. A file without a record keeps everything as far as we know.
FileClassification fileClassification(const format::VoxLinkFile& file);

// Values the classification removed (the complement of what it keeps).
std::vector<tf::ValueInterval> removedValues(const FileClassification& c);
// Values the TF gives opacity that the classification removed: non-empty means the file cannot
// show what the TF asks for, and re-classification would.
std::vector<tf::ValueInterval> visibleButRemoved(const tf::TransferFunction& tf,
                                                 const FileClassification& c);

}  // namespace voxlink::viewer
