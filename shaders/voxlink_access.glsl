// SPDX-License-Identifier: BSD-3-Clause
// Lookups in a VoxLink file on the GPU (format/layout.h, the same steps as format::VoxelLocator):
// brick -> occupied index -> row start -> bit rank within the row mask. The generated
// voxlink_sections.glsl declares the buffers (render/gl/detail/section_buffers.h: the voxel
// sections unchanged, brick tables derived at load time in place of BOCC, BRNK and BVOX; split into
// chunks where one exceeds a storage block) and the accessors rowGroup() (row aprons on GPUs),
// rowWord() (other bricks up to 16^3) or rowsWord() and maskWord() (32^3), voxelWord(),
// valuWord() (values wider than 8 bits), brickIndexWord(), dualBoxWord(), brickEntry().
#include "voxlink_sections.glsl"

// VXL_N (brick size) and VXL_AXIS (predominant axis) come as defines.

uniform ivec3 uBrickGrid;

// Index of the brick at cell b among the occupied bricks, or -1 when it is empty
// (render/brick_lookup.h). The table covers the box of the occupied bricks
// (kVxlIndexLo/kVxlIndexSize, generated): outside it every brick is empty, without a read.
int occupiedIndex(ivec3 b) {
  ivec3 r = b - kVxlIndexLo;
  if (any(lessThan(r, ivec3(0))) || any(greaterThanEqual(r, kVxlIndexSize))) return -1;
  return int(brickIndexWord(
      (uint(r.z) * uint(kVxlIndexSize.y) + uint(r.y)) * uint(kVxlIndexSize.x) + uint(r.x)));
}

// First voxel (BVOX) of occupied brick k.
uint firstVoxel(uint k) { return brickEntry(k).y; }

uint u16At(uint word, uint i) { return (word >> ((i & 1u) << 4u)) & 0xFFFFu; }

// One row (list) of an occupied brick: its mask bits and the index of its first voxel.
struct Row {
  uint bits;
  uint first;
};

// A row of occupied brick k: its mask bits (x) and the index of its first voxel among the
// brick's voxels (y). Bricks up to 16^3 read both from one row word (render/gl/detail/row_words.h),
// 32^3 bricks from MASK and ROWS.
#if VXL_ROW_APRON
uvec2 rowInfoWithApron(uint k, uint row);
#endif
uvec2 rowInfo(uint k, uint row) {
  const uint n = uint(VXL_N);
#if VXL_ROW_APRON
  return rowInfoWithApron(k, row) & uvec2((1u << n) - 1u, 0xFFFFFFFFu);
#elif VXL_N <= 16
  uint word = rowWord(k * n * n + row);
  return uvec2(word & ((1u << n) - 1u), word >> n);
#else
  uint r = k * n * n + row;
  return uvec2(maskWord(k * (n * n * n / 32u) + row), u16At(rowsWord(r >> 1u), r));
#endif
}

#if VXL_ROW_APRON
// rowInfo with the apron bit as mask bit n: whether the brick next along w holds the voxel at
// depth 0 of this row, which then follows the row's voxels (row_words.h). Row groups: row j of
// a group of 4 starts where row 0 does plus the bits of rows 0..j-1 in the group's word 0.
uvec2 rowInfoWithApron(uint k, uint row) {
  const uint n = uint(VXL_N);
#if VXL_ROW_GROUPS
  uvec2 group = rowGroup((k * n * n + row) >> 2u);
  uint j = row & 3u;
  uint before = (((1u << (j * n)) - 1u) | ((1u << j) - 1u) << (3u * n)) & group.x;
  uint low = ((group.x >> (j * n)) & ((1u << n) - 1u)) | ((group.x >> (3u * n + j)) & 1u) << n;
  uint bits = j == 3u ? group.y & ((2u << n) - 1u) : low;
  return uvec2(bits, (group.y >> (n + 1u)) + uint(bitCount(before)));
#else
  uint word = rowWord(k * n * n + row);
  return uvec2(word & ((2u << n) - 1u), word >> (n + 1u));
#endif
}
#endif

// The file-wide index of a row's first voxel from rowInfo's start: row words of bricks up to 8^3
// already hold it (VXL_ROW_GLOBAL, render/gl/detail/row_words.h), otherwise the brick's first
// voxel `base` is added.
uint rowFirst(uint base, uint start) {
#if VXL_N <= 16 && VXL_ROW_GLOBAL
  return start;
#else
  return base + start;
#endif
}

// Mask bits and first voxel of a row.
Row fetchRow(uint k, uint row) {
  uvec2 info = rowInfo(k, row);
  if (info.x == 0u) return Row(0u, 0u);
#if VXL_N <= 16 && VXL_ROW_GLOBAL
  return Row(info.x, info.y);
#else
  return Row(info.x, firstVoxel(k) + info.y);
#endif
}

// Voxel index of depth d in a row, or -1: the next voxel along the predominant axis is the next
// list element; a depth in the row is found by counting the set bits before it.
int voxelInRow(Row row, uint depth) {
  if (((row.bits >> depth) & 1u) == 0u) return -1;
  uint before = depth == 0u ? 0u : bitCount(row.bits << (32u - depth));
  return int(row.first + before);
}

uint rowOfLocal(ivec3 local) { return uint(local[VXL_V]) * uint(VXL_N) + uint(local[VXL_U]); }

// Index of the voxel at index-space cell p, or -1 (outside the volume or not stored).
int findVoxel(ivec3 p) {
  if (!insideGrid(p, uDims)) return -1;
  ivec3 b = p / VXL_N;
  int k = occupiedIndex(b);
  if (k < 0) return -1;
  ivec3 local = p - b * VXL_N;
  return voxelInRow(fetchRow(uint(k), rowOfLocal(local)), uint(local[VXL_W]));
}

// A voxel's word (render/gl/detail/voxel_words.h): gradient direction, and the value of an
// 8-bit file in the top byte, so that one fetch gives both.
uint storedBitsOf(uint voxel, uint word) {
#if VXL_VALUE_BYTES == 1
  return word >> 24u;
#elif VXL_VALUE_BYTES == 2
  return u16At(valuWord(voxel >> 1u), voxel);
#else
  return valuWord(voxel);
#endif
}

uint storedBits(uint voxel) {
#if VXL_VALUE_BYTES == 1
  return voxelWord(voxel) >> 24u;
#else
  return storedBitsOf(voxel, 0u);
#endif
}

// Gradient direction of a voxel word, or zero: three 8-bit signed integers, unit length to
// within 1 %, used without normalizing (render/gl/detail/voxel_words.h).
vec3 directionOfWord(uint word) {
  int w = int(word);
  return vec3(bitfieldExtract(w, 0, 8), bitfieldExtract(w, 8, 8), bitfieldExtract(w, 16, 8)) *
         (1.0 / 127.0);
}

// directionOfWord(word) * scale, with the 1/127 folded into the scale: 2 multiplies fewer per
// trilinear corner (docs/rendering-trilinear-profile.md, sixth session).
vec3 scaledDirectionOfWord(uint word, float scale) {
  int w = int(word);
  return vec3(bitfieldExtract(w, 0, 8), bitfieldExtract(w, 8, 8), bitfieldExtract(w, 16, 8)) *
         (scale * (1.0 / 127.0));
}
