// SPDX-License-Identifier: BSD-3-Clause
// World-space axis vectors of a grid (NRRD space directions, DICOM orientation, NIfTI sform,
// MetaImage TransformMatrix). VoxLink serves voxels in index order with a spacing per axis, so a
// reader keeps the vector lengths and says in a note when the axes are not +x, +y, +z.
#pragma once

#include <array>
#include <string>
#include <string_view>

namespace voxlink::sources {

using Vec3 = std::array<double, 3>;

struct AxesSummary {
  Vec3 lengths{0, 0, 0};
  // Empty when axis i runs along +i for every i; otherwise a sentence for VolumeInfo::notes.
  std::string note;
};

// `source` names the field in the note ("space directions", "ImageOrientationPatient").
AxesSummary summarizeAxes(const std::array<Vec3, 3>& axes, std::string_view source);

double length(const Vec3& v);
double dot(const Vec3& a, const Vec3& b);
Vec3 cross(const Vec3& a, const Vec3& b);

}  // namespace voxlink::sources
