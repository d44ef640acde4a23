// SPDX-License-Identifier: BSD-3-Clause
#include "convert/converter.h"

#include <bit>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <future>
#include <vector>

#include "base/parallel_for.h"
#include "convert/detail/brick_count_pass.h"
#include "convert/detail/brick_encode_pass.h"
#include "convert/detail/converter_meta.h"
#include "convert/detail/keep_rule.h"
#include "convert/detail/rank_exchange.h"
#include "convert/detail/slab_window.h"
#include "convert/detail/value_mapping.h"
#include "format/bricked_volume.h"
#include "format/file_writer.h"

namespace voxlink::convert {

using sources::VolumeInfo;
using sources::VolumeSource;

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct Passes {
  VolumeSource& source;
  const ConvertOptions& options;
  base::RankGroup& ranks;
  GridShape shape{};
  uint32_t slabLayers = 1;  // brick layers per slab
  LayerShare share;         // this rank's brick layers
  unsigned workers;         // threads the passes run on: per-thread results are this many
  ConvertSummary summary;

  Passes(VolumeSource& s, const ConvertOptions& o)
      : source(s),
        options(o),
        ranks(o.ranks ? *o.ranks : base::singleProcess()),
        workers(base::threadCount(o.threads)) {}

  uint64_t rowsPerLayer() const { return shape.grid[1]; }
  uint64_t brickBegin() const { return uint64_t{share.begin} * shape.grid[1] * shape.grid[0]; }
  double done(uint32_t bz1) const {
    return share.end > share.begin ? double(bz1 - share.begin) / (share.end - share.begin) : 1.0;
  }

  Status checkCancel() const {
    if (options.cancel && options.cancel->load())
      return makeError(ErrorCode::kCancelled, source.info().path, ": conversion cancelled");
    return Status::ok();
  }
  void report(double fraction, const char* stage) const {
    if (options.progress) options.progress(fraction, stage);
  }

  template <class T, class Keep>
  Result<BrickCensus> count(const Keep& keep);
  template <class T, class Keep>
  Status encode(const Keep& keep, const BrickCensus& census, const ValueMapping& mapping,
                format::FileWriter& writer, EncodeStats& total);
};

template <class T, class Keep>
Result<BrickCensus> Passes::count(const Keep& keep) {
  const VolumeInfo& info = source.info();
  const uint32_t n = shape.n;
  BrickCensus census;
  const uint64_t bricks = uint64_t{shape.grid[0]} * shape.grid[1] * (share.end - share.begin);
  census.counts.assign(bricks, 0);
  const bool trackRange = sizeof(T) > 1;
  SlabWindow window(source, 0);
  VOXLINK_RETURN_IF_ERROR(window.rewind());
  std::vector<CountResult> results(workers);
  for (uint32_t bz0 = share.begin; bz0 < share.end; bz0 += slabLayers) {
    VOXLINK_RETURN_IF_ERROR(checkCancel());
    const uint32_t bz1 = std::min(share.end, bz0 + slabLayers);
    VOXLINK_RETURN_IF_ERROR(window.load(bz0 * n, std::min(info.dims[2], bz1 * n)));
    base::parallelFor(
        uint64_t{bz1 - bz0} * rowsPerLayer(), workers, [&](uint64_t job, unsigned worker) {
          const uint32_t bz = bz0 + static_cast<uint32_t>(job / rowsPerLayer());
          const uint32_t by = static_cast<uint32_t>(job % rowsPerLayer());
          uint16_t* counts = census.counts.data() +
                             (uint64_t{bz - share.begin} * shape.grid[1] + by) * shape.grid[0];
          countBrickRow<T>(BrickRow{window, shape, bz, by}, keep, trackRange, counts,
                           results[worker]);
        });
    window.release();
    for (const CountResult& r : results) {
      if (r.nonFinite)
        return makeError(ErrorCode::kNonFinite, info.path, ": data: value ", r.nonFiniteValue,
                         " at voxel (", r.nonFiniteAt[0], ", ", r.nonFiniteAt[1], ", ",
                         r.nonFiniteAt[2],
                         ") is not finite; VoxLink files hold finite values only (mask or replace "
                         "NaN/Inf first)");
    }
    report(0.25 * done(bz1), "classifying");
  }
  for (const CountResult& r : results) {
    census.keptMin = std::min(census.keptMin, r.keptMin);
    census.keptMax = std::max(census.keptMax, r.keptMax);
    census.keptMinMagnitude = std::min(census.keptMinMagnitude, r.keptMinMagnitude);
  }
  for (uint16_t c : census.counts) {
    census.voxels += c;
    census.occupied += c != 0;
  }
  return census;
}

template <class T, class Keep>
Status Passes::encode(const Keep& keep, const BrickCensus& census, const ValueMapping& mapping,
                      format::FileWriter& writer, EncodeStats& total) {
  const VolumeInfo& info = source.info();
  const uint32_t n = shape.n;
  const uint32_t maskWords = format::maskWordsPerBrick(n);
  const size_t valueSize = storedSize(mapping.type);
  SlabWindow window(source, 1);
  VOXLINK_RETURN_IF_ERROR(window.rewind());
  std::vector<EncodeStats> stats(workers);
  // Two sets of slab buffers: while the workers encode one slab, a writer task checksums and
  // writes the previous one (at most one write in flight, so sections stay in file order).
  struct SlabBuffers {
    std::vector<uint16_t> rows;
    std::vector<uint32_t> masks;
    std::vector<uint8_t> values;
    std::vector<uint16_t> gradients;
    uint64_t k0 = 0, v0 = 0;  // this rank's first brick of the slab, the file's first voxel
    uint64_t brick0 = 0;      // the file's number of brick k0
  };
  SlabBuffers buffers[2];
  std::future<Status> pendingWrite;  // declared after buffers: joined before they go
  auto writeSlab = [&writer, n, maskWords, valueSize](const SlabBuffers& b) -> Status {
    VOXLINK_RETURN_IF_ERROR(writer.write(format::SectionId::kRowStart, b.brick0 * n * n * 2,
                                         b.rows.data(), b.rows.size() * 2));
    VOXLINK_RETURN_IF_ERROR(writer.write(format::SectionId::kRowMask, b.brick0 * maskWords * 4,
                                         b.masks.data(), b.masks.size() * 4));
    VOXLINK_RETURN_IF_ERROR(writer.write(format::SectionId::kValues, b.v0 * valueSize,
                                         b.values.data(), b.values.size()));
    return writer.write(format::SectionId::kGradients, b.v0 * 2, b.gradients.data(),
                        b.gradients.size() * 2);
  };
  unsigned slabsWritten = 0;
  const uint32_t stride = std::max(1u, options.errorSampleStride);
  for (uint32_t bz0 = share.begin; bz0 < share.end; bz0 += slabLayers) {
    VOXLINK_RETURN_IF_ERROR(checkCancel());
    const uint32_t bz1 = std::min(share.end, bz0 + slabLayers);
    // Rows of bricks counted from this rank's first layer.
    const uint64_t rowBegin = uint64_t{bz0 - share.begin} * shape.grid[1];
    const uint64_t rowEnd = uint64_t{bz1 - share.begin} * shape.grid[1];
    const uint64_t k0 = census.firstOccupied[rowBegin];
    const uint64_t k1 =
        rowEnd < census.firstOccupied.size() ? census.firstOccupied[rowEnd] : census.occupied;
    if (k1 == k0) {
      report(0.25 + 0.75 * done(bz1), "writing");
      continue;
    }
    VOXLINK_RETURN_IF_ERROR(window.load(bz0 * n, std::min(info.dims[2], bz1 * n)));
    const uint64_t v0 = census.voxelBase[k0], v1 = census.voxelBase[k1];
    SlabBuffers& b = buffers[slabsWritten++ % 2];  // its last write was waited for below
    b.k0 = k0;
    b.v0 = v0;
    b.brick0 = census.firstBrick + k0;
    b.rows.assign((k1 - k0) * n * n, 0);
    b.masks.assign((k1 - k0) * maskWords, 0);
    b.values.resize((v1 - v0) * valueSize);
    b.gradients.resize(v1 - v0);
    const SlabOutput out{
        k0, v0, b.rows.data(), b.masks.data(), b.values.data(), b.gradients.data()};
    base::parallelFor(rowEnd - rowBegin, workers, [&](uint64_t job, unsigned worker) {
      const uint64_t rowOfBricks = rowBegin + job;
      const uint32_t bz = share.begin + static_cast<uint32_t>(rowOfBricks / shape.grid[1]);
      const uint32_t by = static_cast<uint32_t>(rowOfBricks % shape.grid[1]);
      const uint16_t* counts = census.counts.data() + rowOfBricks * shape.grid[0];
      encodeBrickRow<T>(
          BrickRow{window, shape, bz, by}, keep, mapping,
          RowCensus{counts, census.firstOccupied[rowOfBricks], census.voxelBase.data()}, out,
          stride, stats[worker]);
    });
    window.release();
    for (const EncodeStats& s : stats)
      if (s.countMismatch)
        return makeError(ErrorCode::kCorrupt, info.path,
                         ": data: the source changed between the two passes of the conversion");
    if (pendingWrite.valid()) VOXLINK_RETURN_IF_ERROR(pendingWrite.get());
    // Written while the next slab encodes; with one thread, written now.
    pendingWrite = base::runInBackground(workers, [&writeSlab, &b] { return writeSlab(b); });
    report(0.25 + 0.75 * done(bz1), "writing");
  }
  if (pendingWrite.valid()) VOXLINK_RETURN_IF_ERROR(pendingWrite.get());
  for (const EncodeStats& s : stats) total.add(s);
  return Status::ok();
}

// Runs both passes for source element type T with the fastest keep test that fits. With
// several ranks every step that needs the others is collective and preceded by agree(), so a
// rank that fails makes every rank stop there with its error.
template <class T, class Keep>
Result<ConvertSummary> run(Passes& passes, const Keep& keep, const std::string& outputPath) {
  const VolumeInfo& info = passes.source.info();
  const ConvertOptions& options = passes.options;
  base::RankGroup& ranks = passes.ranks;
  const bool root = ranks.rank() == 0;
  const auto start = Clock::now();
  Result<BrickCensus> counted = passes.template count<T>(keep);
  VOXLINK_RETURN_IF_ERROR(base::agree(ranks, counted.status()));
  BrickCensus census = std::move(counted).value();
  exchangeCounts(ranks, census);
  if (census.totalVoxels > format::kMaxVoxels)
    return makeError(ErrorCode::kTooLarge, info.path, ": classification keeps more than ",
                     format::kMaxVoxels,
                     " voxels, the format's limit; keep fewer values or split the volume");
  numberBricks(census, passes.shape, passes.brickBegin());
  if (sizeof(T) == 1 && census.totalVoxels > 0) {  // 8-bit sources: range not tracked, not needed
    census.keptMin = std::numeric_limits<T>::min();
    census.keptMax = std::numeric_limits<T>::max();
  }
  ConvertSummary& s = passes.summary;
  s.countSeconds = secondsSince(start);
  Result<ValueMapping> chosen =
      chooseValueMapping(info.type, census.keptMin, census.keptMax, options.storedType,
                         options.errorBound, census.keptMinMagnitude);
  if (!chosen) return makeError(chosen.code(), info.path, ": ", chosen.message());
  ValueMapping mapping = *chosen;
  if (info.type == ScalarType::kI8 && mapping.type == StoredType::kU8 && !mapping.quantized)
    mapping.offset = -128;  // the whole i8 range, lossless
  format::VolumeDescription d;
  d.dims = info.dims;
  d.brickSize = options.brickSize;
  d.predominantAxis = options.axis;
  d.valueType = mapping.type;
  d.sourceType = info.type;
  d.spacing = info.spacing;
  d.origin = info.origin;
  d.valueScale = mapping.scale;
  d.valueOffset = mapping.offset;
  d.valueErrorBound = mapping.errorBound;
  VOXLINK_RETURN_IF_ERROR(format::checkDescription(d));
  const format::FileHeader header = format::makeHeader(d, census.totalVoxels, census.totalOccupied);
  VOXLINK_ASSIGN_OR_RETURN(format::FileWriter writer, openSharedWriter(ranks, outputPath, header));

  // Each rank writes the voxel bases of its bricks (the last rank also the end of the last one)
  // and encodes its layers.
  const auto writeStart = Clock::now();
  const bool last = ranks.rank() == ranks.size() - 1;
  Status wrote = writer.write(format::SectionId::kBrickVoxelBase, census.firstBrick * 4,
                              census.voxelBase.data(), (census.occupied + last) * 4);
  EncodeStats local;
  if (wrote) wrote = passes.template encode<T>(keep, census, mapping, writer, local);
  if (wrote && !root) wrote = writer.close();
  VOXLINK_RETURN_IF_ERROR(base::agree(ranks, wrote));
  const uint64_t totalBricks =
      uint64_t{passes.shape.grid[0]} * passes.shape.grid[1] * passes.shape.grid[2];
  const std::vector<uint32_t> occupancy = gatherOccupancy(ranks, census, (totalBricks + 31) / 32);
  const EncodeStats stats = reduceStats(ranks, local);
  const std::vector<format::FileWriter::SectionPart> otherParts = gatherSectionParts(ranks, writer);
  s.voxels = census.totalVoxels;
  s.occupiedBricks = census.totalOccupied;
  s.storedType = mapping.type;
  s.valueMaxAbsError = stats.maxAbsError;
  s.valueMaxRelError = stats.maxRelError;
  s.gradientSamples = stats.gradientSamples;
  s.gradientMeanErrorDeg =
      stats.gradientSamples ? stats.gradientErrorNanoDeg * 1e-9 / stats.gradientSamples : 0.0;
  s.gradientMaxErrorDeg = stats.gradientMaxErrorDeg;
  s.zeroGradients = stats.zeroGradients;
  // Rank 0 writes what spans every rank, checksums, and renames the file into place.
  Status committed;
  if (root) {
    const std::vector<uint32_t> rank = format::rankFromOccupancy(occupancy);
    committed =
        writer.write(format::SectionId::kBrickOccupancy, 0, occupancy.data(), occupancy.size() * 4);
    if (committed)
      committed = writer.write(format::SectionId::kBrickRank, 0, rank.data(), rank.size() * 4);
    format::FileHeader& h = writer.header();
    h.valueMin = census.totalVoxels ? stats.valueMin : 0.0;
    h.valueMax = census.totalVoxels ? stats.valueMax : 0.0;
    h.valueMaxAbsError = stats.maxAbsError;
    h.valueMaxRelError = stats.maxRelError;
    if (committed) committed = writer.commit(metaJson(info, options, mapping, s), otherParts);
  }
  VOXLINK_RETURN_IF_ERROR(base::agree(ranks, committed));
  s.writeSeconds = secondsSince(writeStart);
  s.seconds = secondsSince(start);
  std::error_code ec;  // other ranks may not see the file yet (another node's view of the disk)
  const uintmax_t bytes = std::filesystem::file_size(outputPath, ec);
  if (ec && root) return makeError(ErrorCode::kIo, outputPath, ": ", ec.message());
  s.bytes = ec ? 0 : bytes;
  passes.report(1.0, "done");
  return s;
}

template <class T>
Result<ConvertSummary> runForType(Passes& passes, const std::string& outputPath) {
  const Classification& c = passes.options.classification;
  if constexpr (std::is_integral_v<T>) {
    if (c.kind == Classification::Kind::kAll)
      return run<T>(passes,
                    RangeKeep<T>{std::numeric_limits<T>::min(), std::numeric_limits<T>::max()},
                    outputPath);
    T lo, hi;
    if (!c.mean && c.keep.size() == 1) {
      if (!integerRange<T>(c.keep[0], lo, hi)) lo = 1, hi = 0;  // keeps nothing
      return run<T>(passes, RangeKeep<T>{lo, hi}, outputPath);
    }
    if constexpr (sizeof(T) <= 2) {
      const std::vector<uint8_t> table = keepTable<T>(c);
      return run<T>(passes, TableKeep<T>{table.data()}, outputPath);
    }
  }
  return run<T>(passes, GeneralKeep<T>{&c}, outputPath);
}

}  // namespace

Result<ConvertSummary> convertVolume(VolumeSource& source, const ConvertOptions& options,
                                     const std::string& outputPath) {
  const VolumeInfo& info = source.info();
  VOXLINK_RETURN_IF_ERROR(base::checkThreadCount(options.threads, "--threads"));
  if (!format::isValidBrickSize(options.brickSize))
    return makeError(ErrorCode::kInvalidArgument, "--brick ", options.brickSize,
                     ": expected 4, 8, 16 or 32");
  if (options.classification.kind != Classification::Kind::kAll &&
      options.classification.keep.empty())
    return makeError(ErrorCode::kInvalidArgument, info.path,
                     ": the classification keeps no values (", options.classification.describe(),
                     ")");
  for (int a = 0; a < 3; ++a) {
    if (info.dims[a] == 0 || info.dims[a] > format::kMaxDim)
      return makeError(ErrorCode::kTooLarge, info.path, ": dims[", a, "] = ", info.dims[a],
                       ": expected 1..", format::kMaxDim);
  }
  Passes passes(source, options);
  GridShape& g = passes.shape;
  g.n = options.brickSize;
  for (int a = 0; a < 3; ++a) {
    g.dims[a] = info.dims[a];
    g.grid[a] = (info.dims[a] + g.n - 1) / g.n;
    g.spacing[a] = info.spacing[a];
  }
  g.frame = format::axisFrame(options.axis);
  passes.slabLayers = std::max(1u, (std::max(options.slabSlices, 1u) + g.n - 1) / g.n);
  passes.share = layerShare(g.grid[2], passes.ranks.rank(), passes.ranks.size());
  passes.summary.sourceVoxels = info.voxelCount();
  passes.summary.bricks = uint64_t{g.grid[0]} * g.grid[1] * g.grid[2];
  return dispatchScalar(info.type, [&](auto t) {
    using T = decltype(t);
    return runForType<T>(passes, outputPath);
  });
}

}  // namespace voxlink::convert
