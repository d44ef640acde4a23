// SPDX-License-Identifier: BSD-3-Clause
// Constants and small helpers shared by every VoxLink shader.
// Mirrors render/render_model.h (float64 on the CPU side).

const float kBig = 1e30;
// Direction components smaller than this count as zero: the ray never crosses those planes.
const float kParallelEpsilon = 1e-12;
// Opacity 1 is held just below 1 so -ln(1 - alpha) stays finite (kMaxUnitAlpha in C++).
const float kMaxUnitAlpha = 0.999999;

// Axis (0, 1, 2) of the smallest component; ties go to the later axis, as in walkVoxels().
int minAxis(vec3 v) {
  return v.x < v.y ? (v.x < v.z ? 0 : 2) : (v.y < v.z ? 1 : 2);
}

bool insideGrid(ivec3 cell, ivec3 size) {
  return all(greaterThanEqual(cell, ivec3(0))) && all(lessThan(cell, size));
}

// Axes of VoxLink space: rows (lists) run along w, the predominant axis; u = (w + 1) % 3 and
// v = (w + 2) % 3 (format/layout.h). Dense volumes use w = z.
#ifndef VXL_AXIS
#define VXL_AXIS 2
#endif
#define VXL_W VXL_AXIS
#define VXL_U ((VXL_AXIS + 1) % 3)
#define VXL_V ((VXL_AXIS + 2) % 3)
