#include "format/gradient_predictor.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include "format/brick_rows.h"
#include "format/gradient_codec.h"
#include "format/mask_rank.h"
#include "format/parallel_for.h"
#include "format/voxel_locator.h"

namespace voxlink::format {
namespace {

// Compile-time cosine and sine: a fixed sequence of IEEE double operations, so every compiler
// and machine gets the same table bits (a libm call could differ in the last bit).
constexpr double kPi = 3.14159265358979323846;

constexpr double taylorCos(double x) {  // |x| <= pi/2
  double sum = 1, term = 1;
  for (int k = 1; k <= 30; ++k) {
    term *= -x * x / ((2.0 * k - 1) * (2.0 * k));
    sum += term;
  }
  return sum;
}
constexpr double taylorSin(double x) {  // |x| <= pi/2
  double sum = x, term = x;
  for (int k = 1; k <= 30; ++k) {
    term *= -x * x / ((2.0 * k) * (2.0 * k + 1));
    sum += term;
  }
  return sum;
}
constexpr double exactCos(double a) {  // 0 <= a <= pi
  return a <= kPi / 2 ? taylorCos(a) : -taylorCos(kPi - a);
}
constexpr double exactSin(double a) {  // 0 <= a <= pi
  return a <= kPi / 2 ? taylorSin(a) : taylorSin(kPi - a);
}

template <int N, bool Sine>
constexpr std::array<double, N> boundaryTable(int steps) {
  std::array<double, N> table{};
  for (int j = 0; j < N; ++j) {
    const double angle = (j + 0.5) * kPi / steps;
    table[j] = Sine ? exactSin(angle) : exactCos(angle);
  }
  return table;
}

// Polar index t = number of boundaries j with cos(theta) < kPolar[j].
constexpr auto kPolar = boundaryTable<kPolarSteps, false>(kPolarSteps);
// Azimuth in the upper half plane: q = number of boundaries j below the direction's angle.
constexpr int kHalfTurn = kAzimuthSteps / 2;
constexpr auto kAzimuthCos = boundaryTable<kHalfTurn, false>(kHalfTurn);
constexpr auto kAzimuthSin = boundaryTable<kHalfTurn, true>(kHalfTurn);

// One occupied brick's neighbourhood as a dense block with a one-cell halo.
struct Scratch {
  std::vector<double> value;
  std::vector<uint32_t> cell;  // padded cell of each of the brick's samples, in file order
  std::vector<uint64_t> slot;  // and its entry in GRAD
  std::vector<double> g[3];
  std::vector<float> gf[3];
  std::vector<uint16_t> guess;
};

class Predictor {
 public:
  explicit Predictor(const VoxLinkFile& f)
      : file_(f),
        h_(f.header()),
        n_(h_.brickSize),
        frame_(axisFrame(f.predominantAxis())),
        maskWords_(maskWordsPerBrick(n_)),
        locator_(f),
        base_(f.brickVoxelBase().data()),
        rowStart_(f.rowStarts().data()),
        mask_(f.rowMaskWords().data()),
        scene_(f.isScene()),
        samples_(scene_ ? MaskRank(f.volumeMaskWords()) : MaskRank()),
        slots_(sampleSlots(h_)) {
    const bool world = (h_.flags & kFlagGradientsInWorldSpace) != 0;
    for (int a = 0; a < 3; ++a) {
      const double s = world ? h_.spacing[a] : 1.0;
      half_[a] = 0.5 / s;
      full_[a] = 1.0 / s;
    }
    fill_ = h_.valueMin - std::abs(h_.valueScale);
    const uint32_t p = n_ + 2;
    stride_ = {1, p, p * p};
  }

  void predictBrick(uint64_t b, uint64_t k, std::span<uint16_t> codes, Scratch& s) const {
    const uint32_t n = n_, p = n + 2;
    // Cells that hold no stored voxel read as the fill value.
    s.value.assign(size_t{p} * p * p, fill_);
    const uint32_t origin[3] = {
        static_cast<uint32_t>(b % h_.brickGrid[0]) * n,
        static_cast<uint32_t>(b / h_.brickGrid[0] % h_.brickGrid[1]) * n,
        static_cast<uint32_t>(b / (uint64_t{h_.brickGrid[0]} * h_.brickGrid[1])) * n};
    // The brick's own voxels, in file order.
    const uint64_t first = base_[k];
    const uint32_t count = static_cast<uint32_t>(base_[k + 1] - first);
    s.cell.resize(count);
    const uint32_t* mask = mask_ + k * maskWords_;
    uint32_t i = 0;
    s.slot.resize(count);
    uint32_t voxel = 0;  // of the brick, in file order
    for (uint32_t row = 0; row < n * n; ++row) {
      for (uint32_t bits = rowBits(mask, n, row); bits != 0; bits &= bits - 1, ++voxel) {
        uint64_t slot;
        double v;
        if (!sample(first + voxel, slot, v)) continue;  // a scene's geometry-only voxel
        uint32_t l[3];
        l[frame_.u] = row % n;
        l[frame_.v] = row / n;
        l[frame_.w] = static_cast<uint32_t>(std::countr_zero(bits));
        const uint32_t c = padded(l[0] + 1, l[1] + 1, l[2] + 1);
        s.value[c] = v;
        s.slot[i] = slot;
        s.cell[i++] = c;
      }
    }
    const uint32_t samples = i;
    // The faces of the six neighbouring bricks that touch this one.
    const uint64_t brickStride[3] = {1, h_.brickGrid[0],
                                     uint64_t{h_.brickGrid[0]} * h_.brickGrid[1]};
    for (int a = 0; a < 3; ++a) {
      if (origin[a] > 0) fillFace(b - brickStride[a], a, -1, s);
      if (origin[a] + n < h_.dims[a]) fillFace(b + brickStride[a], a, 1, s);
    }
    for (int a = 0; a < 3; ++a) {
      s.g[a].resize(count);
      s.gf[a].resize(count);
    }
    s.guess.resize(count);
    // A brick away from the volume's faces takes central differences everywhere.
    bool inside = true;
    for (int a = 0; a < 3; ++a) inside &= origin[a] > 0 && origin[a] + n < h_.dims[a];
    for (uint32_t j = 0; j < samples; ++j) {
      const uint32_t c = s.cell[j];
      double grad[3];
      if (inside) {
        for (int a = 0; a < 3; ++a)
          grad[a] = (s.value[c + stride_[a]] - s.value[c - stride_[a]]) * half_[a];
      } else {
        const uint32_t l[3] = {c % p - 1, c / p % p - 1, c / (p * p) - 1};
        for (int a = 0; a < 3; ++a) {
          const uint32_t at = origin[a] + l[a];
          if (h_.dims[a] == 1) {
            grad[a] = 0;
            continue;
          }
          // One-sided at the volume's faces, as the converter does.
          const bool hasLo = at > 0, hasHi = at + 1 < h_.dims[a];
          const uint32_t st = stride_[a];
          const double lo = hasLo ? s.value[c - st] : s.value[c];
          const double hi = hasHi ? s.value[c + st] : s.value[c];
          grad[a] = (hi - lo) * (hasLo && hasHi ? half_[a] : full_[a]);
        }
      }
      const double big = std::max({std::abs(grad[0]), std::abs(grad[1]), std::abs(grad[2])});
      if (big > 1e30) grad[0] /= big, grad[1] /= big, grad[2] /= big;
      for (int a = 0; a < 3; ++a) {
        s.g[a][j] = grad[a];
        s.gf[a][j] = static_cast<float>(grad[a]);
      }
    }
    encodeGradients(s.gf[0].data(), s.gf[1].data(), s.gf[2].data(), s.guess.data(), samples);
    for (uint32_t j = 0; j < samples; ++j)
      codes[s.slot[j]] = exactGradientCode(s.g[0][j], s.g[1][j], s.g[2][j], s.guess[j]);
  }

 private:
  // Copies the face of neighbouring brick `nb` (on side `side` of axis `a`) that touches the
  // current brick into the halo of s.value, walking the neighbour's rows: a row along the
  // depth axis crosses the face in one cell, a row in the face lies in it whole.
  void fillFace(uint64_t nb, int a, int side, Scratch& s) const {
    const int64_t k = locator_.occupiedIndex(nb);
    if (k < 0) return;
    const uint32_t n = n_;
    const uint32_t* mask = mask_ + static_cast<uint64_t>(k) * maskWords_;
    const uint16_t* rowStart = rowStart_ + static_cast<uint64_t>(k) * n * n;
    const uint64_t first = base_[k];
    const uint32_t inFace = side < 0 ? n - 1 : 0;  // the face's cells, neighbour-local
    const uint32_t halo = side < 0 ? 0 : n + 1;    // where they go in the padded block
    uint32_t q[3];
    q[a] = halo;
    if (a == frame_.w) {
      for (uint32_t row = 0; row < n * n; ++row) {
        const int r = rankInRow(rowBits(mask, n, row), inFace);
        if (r < 0) continue;
        q[frame_.u] = row % n + 1;
        q[frame_.v] = row / n + 1;
        uint64_t slot;
        double v;
        if (sample(first + rowStart[row] + r, slot, v)) s.value[padded(q[0], q[1], q[2])] = v;
      }
      return;
    }
    const bool faceIsU = a == frame_.u;
    for (uint32_t other = 0; other < n; ++other) {
      const uint32_t row = faceIsU ? other * n + inFace : inFace * n + other;
      q[faceIsU ? frame_.v : frame_.u] = other + 1;
      uint64_t i = first + rowStart[row];
      for (uint32_t bits = rowBits(mask, n, row); bits != 0; bits &= bits - 1) {
        q[frame_.w] = static_cast<uint32_t>(std::countr_zero(bits)) + 1;
        uint64_t slot;
        double v;
        if (sample(i++, slot, v)) s.value[padded(q[0], q[1], q[2])] = v;
      }
    }
  }

  uint32_t padded(uint32_t x, uint32_t y, uint32_t z) const {
    return x + y * stride_[1] + z * stride_[2];
  }
  // The volume sample of voxel i and its slot in VALU and GRAD: voxel i itself in a volume
  // file; in a scene its VMSK slot, and none for voxels that hold only geometry.
  // (A slot past VALU's entries, from a mask that disagrees with its count, is no sample:
  // validateStructure refuses such files, this keeps an unvalidated one inside its sections.)
  bool sample(uint64_t voxel, uint64_t& slot, double& v) const {
    if (scene_) {
      if (!samples_.has(voxel)) return false;
      slot = samples_.slot(voxel);
      if (slot >= slots_) return false;
    } else {
      slot = voxel;
    }
    v = file_.value(slot);
    return true;
  }

  const VoxLinkFile& file_;
  const FileHeader& h_;
  uint32_t n_;
  AxisFrame frame_;
  uint32_t maskWords_;
  VoxelLocator locator_;  // occupied index of neighbouring bricks
  const uint32_t* base_;
  const uint16_t* rowStart_;
  const uint32_t* mask_;
  bool scene_;
  MaskRank samples_;  // scenes: VMSK slots
  uint64_t slots_;    // entries of VALU and GRAD
  double half_[3], full_[3];
  double fill_;
  std::array<uint32_t, 3> stride_;
};

}  // namespace

std::span<const double> polarBoundaryCosines() { return kPolar; }
std::span<const double> azimuthBoundaryCosines() { return kAzimuthCos; }
std::span<const double> azimuthBoundarySines() { return kAzimuthSin; }

uint16_t exactGradientCode(double x, double y, double z, uint16_t guess) {
  const double big = std::max({std::abs(x), std::abs(y), std::abs(z)});
  if (!(big > 0) || !std::isfinite(big)) return kZeroGradient;
  if (big > 1e100 || big < 1e-100) x /= big, y /= big, z /= big;  // squares stay finite
  // cos(theta) < kPolar[j] as z < kPolar[j] * length: no division.
  const double length = std::sqrt(x * x + y * y + z * z);
  int t = guess == kZeroGradient ? kPolarSteps / 2 : std::min(guess >> 8, kPolarSteps);
  while (t > 0 && !(z < kPolar[t - 1] * length)) --t;
  while (t < kPolarSteps && z < kPolar[t] * length) ++t;
  if (t == 0 || t == kPolarSteps) return static_cast<uint16_t>(t << 8);
  // Azimuth: fold the lower half plane onto the upper one (negation is exact), then find how
  // many boundary directions lie clockwise of (x, y) by the sign of their cross product.
  const bool lower = y < 0;
  const double ax = lower ? -x : x, ay = lower ? -y : y;
  int q = guess == kZeroGradient ? 0 : (guess & 0xFF) - (lower ? kHalfTurn : 0);
  q = std::clamp(q, 0, kHalfTurn);
  auto above = [&](int j) { return kAzimuthCos[j] * ay - kAzimuthSin[j] * ax > 0; };
  while (q > 0 && !above(q - 1)) --q;
  while (q < kHalfTurn && above(q)) ++q;
  const int p = (q + (lower ? kHalfTurn : 0)) % kAzimuthSteps;
  return static_cast<uint16_t>(t << 8 | p);
}

void predictGradientCodes(const VoxLinkFile& file, std::span<uint16_t> codes, unsigned threads) {
  const Predictor predictor(file);
  // Occupied bricks in file order, so workers can take ranges of them.
  std::vector<uint64_t> bricks;
  bricks.reserve(file.occupiedBrickCount());
  const auto occupancy = file.occupancyWords();
  for (uint64_t w = 0; w < occupancy.size(); ++w)
    for (uint32_t bits = occupancy[w]; bits != 0; bits &= bits - 1)
      bricks.push_back(w * 32 + static_cast<uint64_t>(std::countr_zero(bits)));
  // Batches of bricks, each worker with its own scratch blocks.
  constexpr uint64_t kBatch = 256;
  const uint64_t batches = (bricks.size() + kBatch - 1) / kBatch;
  parallelFor(batches, threads, [&](uint64_t batch) {
    thread_local Scratch scratch;
    const uint64_t end = std::min<uint64_t>((batch + 1) * kBatch, bricks.size());
    for (uint64_t k = batch * kBatch; k < end; ++k)
      predictor.predictBrick(bricks[k], k, codes, scratch);
  });
}

}  // namespace voxlink::format
