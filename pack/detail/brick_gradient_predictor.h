// SPDX-License-Identifier: BSD-3-Clause
// One occupied brick at a time: the gradient predictor of packed files reads the brick's values
// and its one-cell halo into a dense block, takes central differences and encodes them (exactly,
// or the portable float way). Internal to pack/gradient_predictor.cpp, whose entry points (the
// whole file, a range, per voxel) drive it.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

#include "format/brick_rows.h"
#include "format/gradient_codec.h"
#include "format/half.h"
#include "format/mask_rank.h"
#include "format/voxel_locator.h"
#include "format/voxlink_file.h"
#include "pack/detail/central_differences.h"
#include "pack/detail/dense_brick_rows.h"
#include "pack/detail/gradient_boundaries.h"
#include "pack/detail/gradient_predictor.h"
#include "pack/detail/portable_gradient_code.h"

namespace voxlink::pack::detail {

using format::AxisFrame;
using format::axisFrame;
using format::encodeGradients;
using format::FileHeader;
using format::halfToFloat;
using format::kAzimuthSteps;
using format::kFlagGradientsInWorldSpace;
using format::kPolarSteps;
using format::kZeroGradient;
using format::MaskRank;
using format::maskWordsPerBrick;
using format::rankInRow;
using format::rowBits;
using format::sampleSlots;
using format::VoxelLocator;
using format::VoxLinkFile;

// One occupied brick's neighbourhood as a dense block with a one-cell halo.
template <class Real>
struct Scratch {
  std::vector<Real> value;
  std::vector<uint32_t> cell;  // padded cell of each of the brick's samples, in file order
  std::vector<uint64_t> slot;  // and its entry in GRAD
  std::vector<Real> g[3];
  std::vector<float> gf[3];
  std::vector<uint16_t> guess;
  std::vector<uint16_t> sum;     // codes to be added to the output's
  std::vector<float> rowValues;  // the dense path's: the brick's values, then padding
  std::vector<float> block;      // its block, in brick-row order (pack/detail/dense_brick_rows.h)
  // and the differences of consecutive dense bricks' voxels, codes[pendingFirst ...], encoded
  // together (a call per brick would spend a sixth of its time in the loop's remainder)
  std::vector<float> pending[3];
  uint64_t pendingFirst = 0;
  uint32_t pendingCount = 0;
};

// Where the predicted codes go: entries [first, first + size) of GRAD, the whole section or the
// part that a range prediction covers.
struct CodeWindow {
  uint16_t* data;
  uint64_t first = 0;
  uint16_t* at(uint64_t entry) const { return data + (entry - first); }
};

// Real = double: GradientPrediction::kExact; float: kPortable.
template <class Real>
class Predictor {
 public:
  Predictor(const VoxLinkFile& f, bool allowDense, bool add)
      : add_(add),
        h_(f.header()),
        n_(h_.brickSize),
        frame_(axisFrame(f.predominantAxis())),
        maskWords_(maskWordsPerBrick(n_)),
        locator_(f),
        base_(f.brickVoxelBase().data()),
        rowStart_(f.rowStarts().data()),
        mask_(f.rowMaskWords().data()),
        scene_(f.isScene()),
        valueType_(f.valueType()),
        values_(f.valueBytes()),
        scale_(f.header().valueScale),
        offset_(f.header().valueOffset),
        table_(valueTable(f)),
        samples_(scene_ ? MaskRank(f.volumeMaskWords()) : MaskRank()),
        slots_(sampleSlots(h_)) {
    const bool world = (h_.flags & kFlagGradientsInWorldSpace) != 0;
    for (int a = 0; a < 3; ++a) {
      const double s = world ? h_.spacing[a] : 1.0;
      half_[a] = static_cast<Real>(0.5 / s);
      full_[a] = static_cast<Real>(1.0 / s);
    }
    fill_ = static_cast<Real>(h_.valueMin - std::abs(h_.valueScale));
    const uint32_t p = n_ + 2;
    stride_ = {1, p, p * p};
    brickStride_ = {1, h_.brickGrid[0], uint64_t{h_.brickGrid[0]} * h_.brickGrid[1]};
    if constexpr (std::is_same_v<Real, float>)
      dense_ = allowDense && !scene_ && n_ >= 8 && denseBrickRowsAvailable();
  }

  // Predicts occupied bricks [k0, k1) (their grid indices in `bricks`) into `codes`, with this
  // thread's scratch; any number of threads at once.
  void predictBricks(std::span<const uint64_t> bricks, uint64_t k0, uint64_t k1,
                     CodeWindow codes) const {
    thread_local Scratch<Real> scratch;
    scratch.pendingCount = 0;  // (nothing from a call that an exception ended)
    for (uint64_t k = k0; k < k1; ++k) predictBrick(bricks[k], k, codes, scratch);
    encodePending(codes, scratch);
  }

 private:
  void predictBrick(uint64_t b, uint64_t k, CodeWindow codes, Scratch<Real>& s) const {
    const uint32_t n = n_, p = n + 2;
    if (dense_ && isInside(b)) return predictInside(b, k, codes, s);
    // Cells that hold no stored voxel read as the fill value.
    s.value.assign(size_t{p} * p * p, fill_);
    const uint32_t origin[3] = {brickOrigin(b, 0), brickOrigin(b, 1), brickOrigin(b, 2)};
    // The brick's own voxels, in file order: rows of n cells along the depth axis w.
    const uint64_t first = base_[k];
    const uint32_t count = static_cast<uint32_t>(base_[k + 1] - first);
    s.cell.resize(count);
    s.slot.resize(count);
    const uint32_t* mask = mask_ + k * maskWords_;
    const uint32_t strideU = stride_[frame_.u], strideV = stride_[frame_.v];
    const uint32_t strideW = stride_[frame_.w];
    Real* value = s.value.data();
    uint32_t* cell = s.cell.data();
    uint64_t* slots = s.slot.data();
    uint32_t i = 0, row = 0;
    uint64_t voxel = first;
    for (uint32_t v = 0; v < n; ++v) {
      for (uint32_t u = 0; u < n; ++u, ++row) {
        const uint32_t rowCell = (u + 1) * strideU + (v + 1) * strideV + strideW;
        for (uint32_t bits = rowBits(mask, n, row); bits != 0; bits &= bits - 1, ++voxel) {
          uint64_t slot;
          Real x;
          if (!sample(voxel, slot, x)) continue;  // a scene's geometry-only voxel
          const uint32_t c = rowCell + static_cast<uint32_t>(std::countr_zero(bits)) * strideW;
          value[c] = x;
          slots[i] = slot;
          cell[i++] = c;
        }
      }
    }
    const uint32_t samples = i;
    // The faces of the six neighbouring bricks that touch this one.
    for (int a = 0; a < 3; ++a) {
      if (origin[a] > 0) fillFace(b - brickStride_[a], a, -1, s);
      if (origin[a] + n < h_.dims[a]) fillFace(b + brickStride_[a], a, 1, s);
    }
    for (int a = 0; a < 3; ++a) s.g[a].resize(count);
    Real* g[3] = {s.g[0].data(), s.g[1].data(), s.g[2].data()};
    // A brick away from the volume's faces takes central differences everywhere.
    if (isInside(b)) {
      if constexpr (std::is_same_v<Real, float>)
        centralDifferencesFloat(value, cell, samples, stride_.data(), half_, g[0], g[1], g[2]);
      else
        centralDifferences(value, cell, samples, stride_.data(), half_, g[0], g[1], g[2]);
    } else {
      for (uint32_t j = 0; j < samples; ++j) {
        const uint32_t c = cell[j];
        const uint32_t l[3] = {c % p - 1, c / p % p - 1, c / (p * p) - 1};
        for (int a = 0; a < 3; ++a) {
          const uint32_t at = origin[a] + l[a];
          if (h_.dims[a] == 1) {
            g[a][j] = 0;
            continue;
          }
          // One-sided at the volume's faces, as the converter does.
          const bool hasLo = at > 0, hasHi = at + 1 < h_.dims[a];
          const uint32_t st = stride_[a];
          const Real lo = hasLo ? value[c - st] : value[c];
          const Real hi = hasHi ? value[c + st] : value[c];
          g[a][j] = (hi - lo) * (hasLo && hasHi ? half_[a] : full_[a]);
        }
      }
    }
    if constexpr (std::is_same_v<Real, float>) {
      if (!scene_) {  // a volume's samples are its voxels, in file order
        putPortableCodes(g, codes.at(first), samples, s);
        return;
      }
      s.guess.resize(count);
      portableGradientCodes(g[0], g[1], g[2], s.guess.data(), samples);
      for (uint32_t j = 0; j < samples; ++j) put(*codes.at(slots[j]), s.guess[j]);
    } else {
      for (int a = 0; a < 3; ++a) s.gf[a].resize(count);
      float* gf[3] = {s.gf[0].data(), s.gf[1].data(), s.gf[2].data()};
      for (uint32_t j = 0; j < samples; ++j) {
        const double big = std::max({std::abs(g[0][j]), std::abs(g[1][j]), std::abs(g[2][j])});
        if (big > 1e30) g[0][j] /= big, g[1][j] /= big, g[2][j] /= big;
        for (int a = 0; a < 3; ++a) gf[a][j] = static_cast<float>(g[a][j]);
      }
      s.guess.resize(count);
      encodeGradients(gf[0], gf[1], gf[2], s.guess.data(), samples);
      for (uint32_t j = 0; j < samples; ++j)
        put(*codes.at(slots[j]), exactCode(g[0][j], g[1][j], g[2][j], s.guess[j]));
    }
  }

  uint32_t brickOrigin(uint64_t b, int a) const {
    const uint64_t cell = a == 0   ? b % h_.brickGrid[0]
                          : a == 1 ? b / h_.brickGrid[0] % h_.brickGrid[1]
                                   : b / (uint64_t{h_.brickGrid[0]} * h_.brickGrid[1]);
    return static_cast<uint32_t>(cell) * n_;
  }
  // Whether every voxel of brick b has both neighbours along every axis inside the volume.
  bool isInside(uint64_t b) const {
    for (int a = 0; a < 3; ++a) {
      const uint32_t origin = brickOrigin(b, a);
      if (origin == 0 || origin + n_ >= h_.dims[a]) return false;
    }
    return true;
  }

  // predictBrick for a volume's brick away from the faces, eight cells of a row at a time: the
  // same values in the same cells and the same float operations, in another order.
  void predictInside(uint64_t b, uint64_t k, CodeWindow codes, Scratch<Real>& s) const {
    if constexpr (std::is_same_v<Real, float>) {  // (dense_ is false otherwise)
      const uint32_t n = n_, p = n + 2, cells = n * n * n;
      const uint64_t first = base_[k];
      const uint32_t count = static_cast<uint32_t>(std::min<uint64_t>(base_[k + 1] - first, cells));
      const uint32_t* mask = mask_ + k * maskWords_;
      // Neither buffer is cleared per brick (that was a fifth of the time): the kernels take
      // values[i] only for the mask's i-th set bit, and only the interior and the six faces of
      // the block, all written below (its edges are never read).
      s.rowValues.resize(cells + 8);
      float* rowValues = s.rowValues.data();
      decodeValues(first, count, rowValues);
      // Past them the fill value: a mask with more bits than the brick's count (a file that
      // fails validateStructure, which callers must not pass) then still predicts the same
      // codes whatever earlier bricks left here.
      uint32_t maskBits = 0;
      for (uint32_t w = 0; w < maskWords_; ++w) maskBits += std::popcount(mask[w]);
      std::fill(rowValues + count, rowValues + (maskBits > count ? cells + 8 : count + 8), fill_);
      if (s.block.size() != size_t{p} * p * p) s.block.assign(size_t{p} * p * p, fill_);
      float* block = s.block.data();
      expandBrickRows(mask, n, s.rowValues.data(), fill_, block);
      for (int a = 0; a < 3; ++a) {
        if (a == frame_.w) {
          fillDepthFace(b - brickStride_[a], -1, block);
          fillDepthFace(b + brickStride_[a], 1, block);
        } else {
          fillSideFace(b - brickStride_[a], a, -1, s);
          fillSideFace(b + brickStride_[a], a, 1, s);
        }
      }
      if (first != s.pendingFirst + s.pendingCount || s.pendingCount >= kPendingVoxels)
        encodePending(codes, s);
      if (s.pendingCount == 0) s.pendingFirst = first;
      for (int a = 0; a < 3; ++a) s.pending[a].resize(kPendingVoxels + cells + 8);
      float* g[3];
      for (int a = 0; a < 3; ++a) g[a] = s.pending[a].data() + s.pendingCount;
      const float half[3] = {half_[frame_.w], half_[frame_.u], half_[frame_.v]};
      const uint32_t samples =
          brickCentralDifferences(mask, n, block, half, g[frame_.w], g[frame_.u], g[frame_.v]);
      s.pendingCount += std::min(samples, count);
    }
  }

  // Encodes the dense bricks' differences still waiting in `s`.
  void encodePending(CodeWindow codes, Scratch<Real>& s) const {
    if constexpr (std::is_same_v<Real, float>) {
      if (s.pendingCount > 0) {
        const float* g[3] = {s.pending[0].data(), s.pending[1].data(), s.pending[2].data()};
        putPortableCodes(g, codes.at(s.pendingFirst), s.pendingCount, s);
      }
    }
    s.pendingCount = 0;
  }

  // The code `code` into `slot`, or added to what it holds.
  void put(uint16_t& slot, uint16_t code) const {
    slot = add_ ? static_cast<uint16_t>(slot + code) : code;
  }
  // out[j] = (or +=) the portable code of (g[0][j], g[1][j], g[2][j]) for j < count.
  void putPortableCodes(const Real* const* g, uint16_t* out, uint32_t count,
                        Scratch<Real>& s) const {
    if constexpr (std::is_same_v<Real, float>) {
      if (!add_) return portableGradientCodes(g[0], g[1], g[2], out, count);
      s.sum.resize(count);
      portableGradientCodes(g[0], g[1], g[2], s.sum.data(), count);
      for (uint32_t j = 0; j < count; ++j) out[j] = static_cast<uint16_t>(out[j] + s.sum[j]);
    }
  }

  static constexpr uint32_t kPendingVoxels = 8192;

  // fillFace across the depth axis for the dense path's block, without branching on the
  // cells: a row's first voxel is at its start, its last just before the next row's start.
  void fillDepthFace(uint64_t nb, int side, float* block) const {
    const uint32_t n = n_, p = n + 2, rows = n * n;
    float* cell = block + (side < 0 ? 0 : n + 1) + p * (1 + p);  // (halo, u = 1, v = 1)
    const int64_t k = locator_.occupiedIndex(nb);
    const uint64_t first = k < 0 ? 0 : base_[k];
    const uint64_t count = k < 0 ? 0 : base_[k + 1] - first;
    if (count == 0) {  // no neighbour: the face holds the fill value
      for (uint32_t v = 0; v < n; ++v, cell += 2 * p)
        for (uint32_t u = 0; u < n; ++u, cell += p) *cell = fill_;
      return;
    }
    const uint16_t* rowStart = rowStart_ + static_cast<uint64_t>(k) * rows;
    const uint32_t* mask = mask_ + static_cast<uint64_t>(k) * maskWords_;
    const uint32_t inFace = side < 0 ? n - 1 : 0;
    uint32_t row = 0;
    for (uint32_t v = 0; v < n; ++v, cell += 2 * p)
      for (uint32_t u = 0; u < n; ++u, ++row, cell += p) {
        const uint32_t bits = rowBits(mask, n, row);
        const uint64_t end = row + 1 < rows ? rowStart[row + 1] : count;
        const uint64_t at = std::min<uint64_t>(inFace == 0 ? rowStart[row] : end - 1, count - 1);
        const float x = value(first + at);
        *cell = (bits >> inFace & 1u) != 0 ? x : fill_;
      }
  }

  // fillFace across u or v for the dense path's block: the n rows in the face, their values
  // decoded together, expanded eight cells at a time.
  void fillSideFace(uint64_t nb, int a, int side, Scratch<Real>& s) const {
    const uint32_t n = n_, p = n + 2;
    const uint32_t halo = side < 0 ? 0 : n + 1;
    const bool acrossU = a == frame_.u;  // the rows (inFace, v), else the rows (u, inFace)
    float* cells = s.block.data() + 1 + p * (acrossU ? halo + p : 1 + p * halo);
    const uint32_t step = acrossU ? p * p : p;
    uint32_t bits[32];
    float* values = s.rowValues.data();  // free again: the brick's own rows are expanded
    const int64_t k = locator_.occupiedIndex(nb);
    if (k < 0) {  // no neighbour: the face holds the fill value
      for (uint32_t other = 0; other < n; ++other) std::fill_n(cells + other * step, n, fill_);
      return;
    }
    const uint16_t* rowStart = rowStart_ + static_cast<uint64_t>(k) * n * n;
    const uint32_t* mask = mask_ + static_cast<uint64_t>(k) * maskWords_;
    const uint64_t first = base_[k];
    const uint64_t count = base_[k + 1] - first;
    const uint32_t inFace = side < 0 ? n - 1 : 0;
    uint32_t taken = 0, wanted = 0;
    for (uint32_t other = 0; other < n; ++other) {
      const uint32_t row = acrossU ? other * n + inFace : inFace * n + other;
      const uint64_t start = std::min<uint64_t>(rowStart[row], count);
      bits[other] = rowBits(mask, n, row);
      const uint32_t voxels =
          static_cast<uint32_t>(std::min<uint64_t>(std::popcount(bits[other]), count - start));
      decodeValues(first + start, voxels, values + taken);
      taken += voxels;
      wanted += static_cast<uint32_t>(std::popcount(bits[other]));
    }
    // What the kernel reads past the decoded values (only a file that fails validation takes
    // any of it) is the fill value, not what an earlier brick left.
    std::fill(values + taken, values + std::max(taken, wanted) + 8, fill_);
    expandRows(bits, n, n, values, fill_, cells, step);
  }

  // out[j] = value(first + j) for j < count, the type's switch outside the loop.
  void decodeValues(uint64_t first, uint32_t count, Real* out) const {
    switch (valueType_) {
      case StoredType::kU8:
        return lookUp<uint8_t>(values_ + first, table_.data(), count, out);
      case StoredType::kU16:
      case StoredType::kF16:
        return lookUp<uint16_t>(values_ + 2 * first, table_.data(), count, out);
      default:
        for (uint32_t j = 0; j < count; ++j) out[j] = value(first + j);
    }
  }

  // Copies the face of neighbouring brick `nb` (on side `side` of axis `a`) that touches the
  // current brick into the halo of s.value, walking the neighbour's rows: a row along the
  // depth axis crosses the face in one cell, a row in the face lies in it whole.
  void fillFace(uint64_t nb, int a, int side, Scratch<Real>& s) const {
    const int64_t k = locator_.occupiedIndex(nb);
    if (k < 0) return;
    const uint32_t n = n_;
    const uint32_t* mask = mask_ + static_cast<uint64_t>(k) * maskWords_;
    const uint16_t* rowStart = rowStart_ + static_cast<uint64_t>(k) * n * n;
    const uint64_t first = base_[k];
    const uint32_t inFace = side < 0 ? n - 1 : 0;  // the face's cells, neighbour-local
    const uint32_t halo = side < 0 ? 0 : n + 1;    // where they go in the padded block
    const uint32_t face = halo * stride_[a];
    const uint32_t strideU = stride_[frame_.u], strideV = stride_[frame_.v];
    const uint32_t strideW = stride_[frame_.w];
    Real* value = s.value.data();
    uint64_t slot;
    Real x;
    if (a == frame_.w) {
      uint32_t row = 0;
      for (uint32_t v = 1; v <= n; ++v)
        for (uint32_t u = 1; u <= n; ++u, ++row) {
          const int r = rankInRow(rowBits(mask, n, row), inFace);
          if (r >= 0 && sample(first + rowStart[row] + r, slot, x))
            value[face + u * strideU + v * strideV] = x;
        }
      return;
    }
    const bool faceIsU = a == frame_.u;
    for (uint32_t other = 0; other < n; ++other) {
      const uint32_t row = faceIsU ? other * n + inFace : inFace * n + other;
      const uint32_t rowCell = face + (other + 1) * (faceIsU ? strideV : strideU) + strideW;
      uint64_t i = first + rowStart[row];
      for (uint32_t bits = rowBits(mask, n, row); bits != 0; bits &= bits - 1)
        if (sample(i++, slot, x))
          value[rowCell + static_cast<uint32_t>(std::countr_zero(bits)) * strideW] = x;
    }
  }

  // The volume sample of voxel i and its slot in VALU and GRAD: voxel i itself in a volume
  // file; in a scene its VMSK slot, and none for voxels that hold only geometry.
  // (In a scene, a slot past VALU's entries is no sample. Otherwise the predictor relies on a
  // structurally valid file, as the header says: every caller runs validateStructure first.)
  bool sample(uint64_t voxel, uint64_t& slot, Real& v) const {
    if (scene_) {
      if (!samples_.has(voxel)) return false;
      slot = samples_.slot(voxel);
      if (slot >= slots_) return false;
    } else {
      slot = voxel;
    }
    v = value(slot);
    return true;
  }
  // VoxLinkFile::value(slot) (rounded to Real), through a table of every stored value for 8- and
  // 16-bit types (the same operations give the same bits).
  Real value(uint64_t slot) const {
    switch (valueType_) {
      case StoredType::kU8:
        return table_[values_[slot]];
      case StoredType::kU16:
      case StoredType::kF16: {
        uint16_t x;
        std::memcpy(&x, values_ + 2 * slot, 2);
        return table_[x];
      }
      default: {  // f32, computed here (an inline VoxLinkFile::value from a file built with
                  // FMA could round differently)
        float x;
        std::memcpy(&x, values_ + 4 * slot, 4);
        return static_cast<Real>(double{x} * scale_ + offset_);
      }
    }
  }
  static std::vector<Real> valueTable(const VoxLinkFile& f) {
    const StoredType type = f.valueType();
    const size_t entries = type == StoredType::kU8                                ? 256
                           : type == StoredType::kU16 || type == StoredType::kF16 ? 65536
                                                                                  : 0;
    std::vector<Real> table(entries);
    const double scale = f.header().valueScale, offset = f.header().valueOffset;
    for (size_t i = 0; i < entries; ++i) {
      const double stored =
          type == StoredType::kF16 ? double{halfToFloat(static_cast<uint16_t>(i))} : double(i);
      table[i] = static_cast<Real>(stored * scale + offset);
    }
    return table;
  }

  bool add_;  // add the predicted codes to the output's instead of writing them
  const FileHeader& h_;
  uint32_t n_;
  AxisFrame frame_;
  uint32_t maskWords_;
  VoxelLocator locator_;  // occupied index of neighbouring bricks
  const uint32_t* base_;
  const uint16_t* rowStart_;
  const uint32_t* mask_;
  bool scene_;
  StoredType valueType_;
  const uint8_t* values_;
  double scale_, offset_;
  std::vector<Real> table_;  // every value of an 8- or 16-bit type
  MaskRank samples_;         // scenes: VMSK slots
  uint64_t slots_;           // entries of VALU and GRAD
  Real half_[3], full_[3];
  Real fill_;
  std::array<uint32_t, 3> stride_;       // of the per-voxel path's block (x fastest)
  std::array<uint64_t, 3> brickStride_;  // between neighbouring bricks' indices
  bool dense_ = false;                   // whether inside bricks take the dense path
};

}  // namespace voxlink::pack::detail
