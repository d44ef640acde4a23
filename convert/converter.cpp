#include "convert/converter.h"

#include <bit>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <future>
#include <nlohmann/json.hpp>
#include <system_error>
#include <vector>

#include "convert/brick_count_pass.h"
#include "convert/brick_encode_pass.h"
#include "convert/keep_rule.h"
#include "convert/slab_window.h"
#include "convert/value_mapping.h"
#include "convert/worker_pool.h"
#include "format/file_writer.h"
#include "format/parallel_for.h"

namespace voxlink::convert {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

constexpr const char* kGradientMethod =
    "central differences of source values per world unit, one-sided at the volume border";

// What pass 1 learns: counts per brick, occupied-brick numbering, voxel bases, kept range.
struct BrickCensus {
  std::vector<uint16_t> counts;         // per grid brick
  std::vector<uint32_t> occupancy;      // BOCC
  std::vector<uint32_t> voxelBase;      // BVOX, K + 1 entries
  std::vector<uint64_t> firstOccupied;  // per row of bricks (bz*gy + by): occupied bricks before
  uint64_t voxels = 0;
  uint64_t occupied = 0;
  double keptMin = INFINITY, keptMax = -INFINITY;
  double keptMinMagnitude = INFINITY;  // smallest nonzero |value| kept (f64 sources only)
};

struct Passes {
  VolumeSource& source;
  const ConvertOptions& options;
  GridShape shape{};
  uint32_t slabLayers = 1;  // brick layers per slab
  WorkerPool pool;
  ConvertSummary summary;

  Passes(VolumeSource& s, const ConvertOptions& o) : source(s), options(o), pool(o.threads) {}

  uint32_t layers() const { return shape.grid[2]; }
  uint64_t rowsPerLayer() const { return shape.grid[1]; }

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
  const uint64_t bricks = uint64_t{shape.grid[0]} * shape.grid[1] * shape.grid[2];
  census.counts.assign(bricks, 0);
  const bool trackRange = sizeof(T) > 1;
  SlabWindow window(source, 0);
  VOXLINK_RETURN_IF_ERROR(window.rewind());
  std::vector<CountResult> results(pool.size());
  for (uint32_t bz0 = 0; bz0 < layers(); bz0 += slabLayers) {
    VOXLINK_RETURN_IF_ERROR(checkCancel());
    const uint32_t bz1 = std::min(layers(), bz0 + slabLayers);
    VOXLINK_RETURN_IF_ERROR(window.load(bz0 * n, std::min(info.dims[2], bz1 * n)));
    pool.run(uint64_t{bz1 - bz0} * rowsPerLayer(), [&](size_t job, unsigned worker) {
      const uint32_t bz = bz0 + static_cast<uint32_t>(job / rowsPerLayer());
      const uint32_t by = static_cast<uint32_t>(job % rowsPerLayer());
      uint16_t* counts = census.counts.data() + (uint64_t{bz} * shape.grid[1] + by) * shape.grid[0];
      countBrickRow<T>(BrickRow{window, shape, bz, by}, keep, trackRange, counts, results[worker]);
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
    report(0.25 * bz1 / layers(), "classifying");
  }
  for (const CountResult& r : results) {
    census.keptMin = std::min(census.keptMin, r.keptMin);
    census.keptMax = std::max(census.keptMax, r.keptMax);
    census.keptMinMagnitude = std::min(census.keptMinMagnitude, r.keptMinMagnitude);
  }
  // Number the occupied bricks and give each its first voxel.
  census.occupancy.assign((bricks + 31) / 32, 0);
  census.firstOccupied.resize(uint64_t{shape.grid[1]} * shape.grid[2]);
  census.voxelBase.reserve(bricks / 8 + 2);
  for (uint64_t b = 0; b < bricks; ++b) {
    if (b % shape.grid[0] == 0) census.firstOccupied[b / shape.grid[0]] = census.occupied;
    if (census.counts[b] == 0) continue;
    census.occupancy[b >> 5] |= 1u << (b & 31);
    if (census.voxels > format::kMaxVoxels) break;
    census.voxelBase.push_back(static_cast<uint32_t>(census.voxels));
    census.voxels += census.counts[b];
    ++census.occupied;
  }
  if (census.voxels > format::kMaxVoxels)
    return makeError(ErrorCode::kTooLarge, info.path, ": classification keeps more than ",
                     format::kMaxVoxels,
                     " voxels, the format's limit; keep fewer values or split the volume");
  census.voxelBase.push_back(static_cast<uint32_t>(census.voxels));
  if (sizeof(T) == 1 && census.voxels > 0) {  // 8-bit sources: range not tracked, not needed
    census.keptMin = std::numeric_limits<T>::min();
    census.keptMax = std::numeric_limits<T>::max();
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
  std::vector<EncodeStats> stats(pool.size());
  // Two sets of slab buffers: while the workers encode one slab, a writer task checksums and
  // writes the previous one (at most one write in flight, so sections stay in file order).
  struct SlabBuffers {
    std::vector<uint16_t> rows;
    std::vector<uint32_t> masks;
    std::vector<uint8_t> values;
    std::vector<uint16_t> gradients;
    uint64_t k0 = 0, v0 = 0;
  };
  SlabBuffers buffers[2];
  std::future<Status> pendingWrite;  // declared after buffers: joined before they go
  auto writeSlab = [&writer, n, maskWords, valueSize](const SlabBuffers& b) -> Status {
    VOXLINK_RETURN_IF_ERROR(writer.write(format::SectionId::kRowStart, b.k0 * n * n * 2,
                                         b.rows.data(), b.rows.size() * 2));
    VOXLINK_RETURN_IF_ERROR(writer.write(format::SectionId::kRowMask, b.k0 * maskWords * 4,
                                         b.masks.data(), b.masks.size() * 4));
    VOXLINK_RETURN_IF_ERROR(writer.write(format::SectionId::kValues, b.v0 * valueSize,
                                         b.values.data(), b.values.size()));
    return writer.write(format::SectionId::kGradients, b.v0 * 2, b.gradients.data(),
                        b.gradients.size() * 2);
  };
  unsigned slabsWritten = 0;
  const uint32_t stride = std::max(1u, options.errorSampleStride);
  for (uint32_t bz0 = 0; bz0 < layers(); bz0 += slabLayers) {
    VOXLINK_RETURN_IF_ERROR(checkCancel());
    const uint32_t bz1 = std::min(layers(), bz0 + slabLayers);
    const uint64_t rowBegin = uint64_t{bz0} * shape.grid[1];
    const uint64_t rowEnd = uint64_t{bz1} * shape.grid[1];
    const uint64_t k0 = census.firstOccupied[rowBegin];
    const uint64_t k1 =
        rowEnd < census.firstOccupied.size() ? census.firstOccupied[rowEnd] : census.occupied;
    if (k1 == k0) {
      report(0.25 + 0.75 * bz1 / layers(), "writing");
      continue;
    }
    VOXLINK_RETURN_IF_ERROR(window.load(bz0 * n, std::min(info.dims[2], bz1 * n)));
    const uint64_t v0 = census.voxelBase[k0], v1 = census.voxelBase[k1];
    SlabBuffers& b = buffers[slabsWritten++ % 2];  // its last write was waited for below
    b.k0 = k0;
    b.v0 = v0;
    b.rows.assign((k1 - k0) * n * n, 0);
    b.masks.assign((k1 - k0) * maskWords, 0);
    b.values.resize((v1 - v0) * valueSize);
    b.gradients.resize(v1 - v0);
    const SlabOutput out{
        k0, v0, b.rows.data(), b.masks.data(), b.values.data(), b.gradients.data()};
    pool.run(rowEnd - rowBegin, [&](size_t job, unsigned worker) {
      const uint64_t rowOfBricks = rowBegin + job;
      const uint32_t bz = static_cast<uint32_t>(rowOfBricks / shape.grid[1]);
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
    try {
      pendingWrite = std::async(std::launch::async, writeSlab, std::cref(b));
    } catch (const std::system_error&) {  // no thread to spare (task or address-space limits)
      VOXLINK_RETURN_IF_ERROR(writeSlab(b));
    }
    report(0.25 + 0.75 * bz1 / layers(), "writing");
  }
  if (pendingWrite.valid()) VOXLINK_RETURN_IF_ERROR(pendingWrite.get());
  for (const EncodeStats& s : stats) {
    total.valueMin = std::min(total.valueMin, s.valueMin);
    total.valueMax = std::max(total.valueMax, s.valueMax);
    total.maxAbsError = std::max(total.maxAbsError, s.maxAbsError);
    total.maxRelError = std::max(total.maxRelError, s.maxRelError);
    total.gradientSamples += s.gradientSamples;
    total.gradientErrorNanoDeg += s.gradientErrorNanoDeg;
    total.gradientMaxErrorDeg = std::max(total.gradientMaxErrorDeg, s.gradientMaxErrorDeg);
    total.zeroGradients += s.zeroGradients;
  }
  return Status::ok();
}

nlohmann::ordered_json sourceJson(const VolumeInfo& info, const OpenOptions& open) {
  std::error_code ec;
  const auto absolute = std::filesystem::absolute(info.path, ec);
  nlohmann::ordered_json j;
  j["path"] = ec ? info.path : absolute.lexically_normal().string();
  j["format"] = info.format;
  j["type"] = std::string(scalarName(info.type));
  j["dims"] = info.dims;
  j["spacing"] = info.spacing;
  j["origin"] = info.origin;
  j["notes"] = info.notes;
  if (const auto& r = info.rescale)  // only rescaling readers: other files' META is unchanged
    j["rescale"] = {{"field", r->field},
                    {"stored_type", r->storedType},
                    {"slope", {r->minSlope, r->maxSlope}},
                    {"intercept", {r->minIntercept, r->maxIntercept}}};
  nlohmann::ordered_json o;
  if (!open.format.empty()) o["format"] = open.format;
  if (open.dims) o["dims"] = *open.dims;
  if (open.type) o["type"] = std::string(scalarName(*open.type));
  if (open.type || open.dims) o["endian"] = open.endian == Endian::kLittle ? "little" : "big";
  if (open.headerBytes) o["header_bytes"] = open.headerBytes;
  if (open.spacing) o["spacing"] = *open.spacing;
  j["open_options"] = o.empty() ? nlohmann::ordered_json::object() : o;
  return j;
}

std::string metaJson(const VolumeInfo& info, const ConvertOptions& options,
                     const ValueMapping& mapping, const ConvertSummary& s) {
  nlohmann::ordered_json j;
  j["generator"] = "voxlink 0.1.0";
  j["source"] = sourceJson(info, options.sourceOptions);
  j["classification"] = classificationToJson(options.classification);
  j["bricks"] = {{"size", options.brickSize},
                 {"predominant_axis", std::string(1, "xyz"[static_cast<int>(options.axis)])}};
  j["values"] = {{"stored_type", std::string(storedName(mapping.type))},
                 {"scale", mapping.scale},
                 {"offset", mapping.offset},
                 {"choice", mapping.reason},
                 {"error_bound", mapping.errorBound},
                 {"max_abs_error", s.valueMaxAbsError},
                 {"max_rel_error", s.valueMaxRelError}};
  j["gradients"] = {{"method", kGradientMethod},
                    {"codec", "polar16"},
                    {"zero", s.zeroGradients},
                    {"error_deg",
                     {{"mean", s.gradientMeanErrorDeg},
                      {"max", s.gradientMaxErrorDeg},
                      {"samples", s.gradientSamples},
                      {"sample_stride", options.errorSampleStride}}}};
  return j.dump(2);
}

// Runs both passes for source element type T with the fastest keep test that fits.
template <class T, class Keep>
Result<ConvertSummary> run(Passes& passes, const Keep& keep, const std::string& outputPath) {
  const VolumeInfo& info = passes.source.info();
  const ConvertOptions& options = passes.options;
  const auto start = Clock::now();
  VOXLINK_ASSIGN_OR_RETURN(BrickCensus census, passes.template count<T>(keep));
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
  const format::FileHeader header = format::makeHeader(d, census.voxels, census.occupied);
  VOXLINK_ASSIGN_OR_RETURN(format::FileWriter writer,
                           format::FileWriter::create(outputPath, header));
  const std::vector<uint32_t> rank = format::rankFromOccupancy(census.occupancy);
  VOXLINK_RETURN_IF_ERROR(writer.write(format::SectionId::kBrickOccupancy, 0,
                                       census.occupancy.data(), census.occupancy.size() * 4));
  VOXLINK_RETURN_IF_ERROR(
      writer.write(format::SectionId::kBrickRank, 0, rank.data(), rank.size() * 4));
  VOXLINK_RETURN_IF_ERROR(writer.write(format::SectionId::kBrickVoxelBase, 0,
                                       census.voxelBase.data(), census.voxelBase.size() * 4));

  const auto writeStart = Clock::now();
  EncodeStats stats;
  VOXLINK_RETURN_IF_ERROR(passes.template encode<T>(keep, census, mapping, writer, stats));
  s.voxels = census.voxels;
  s.occupiedBricks = census.occupied;
  s.storedType = mapping.type;
  s.valueMaxAbsError = stats.maxAbsError;
  s.valueMaxRelError = stats.maxRelError;
  s.gradientSamples = stats.gradientSamples;
  s.gradientMeanErrorDeg =
      stats.gradientSamples ? stats.gradientErrorNanoDeg * 1e-9 / stats.gradientSamples : 0.0;
  s.gradientMaxErrorDeg = stats.gradientMaxErrorDeg;
  s.zeroGradients = stats.zeroGradients;
  format::FileHeader& h = writer.header();
  h.valueMin = census.voxels ? stats.valueMin : 0.0;
  h.valueMax = census.voxels ? stats.valueMax : 0.0;
  h.valueMaxAbsError = stats.maxAbsError;
  h.valueMaxRelError = stats.maxRelError;
  VOXLINK_RETURN_IF_ERROR(writer.commit(metaJson(info, options, mapping, s)));
  s.writeSeconds = secondsSince(writeStart);
  s.seconds = secondsSince(start);
  s.bytes = std::filesystem::file_size(outputPath);
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
  VOXLINK_RETURN_IF_ERROR(format::checkThreadCount(options.threads, "--threads"));
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
  passes.summary.sourceVoxels = info.voxelCount();
  passes.summary.bricks = uint64_t{g.grid[0]} * g.grid[1] * g.grid[2];
  return dispatchScalar(info.type, [&](auto t) {
    using T = decltype(t);
    return runForType<T>(passes, outputPath);
  });
}

}  // namespace voxlink::convert
