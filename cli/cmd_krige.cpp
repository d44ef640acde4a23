// SPDX-License-Identifier: BSD-3-Clause
// voxlink krige SAMPLES -o GRID.nhdr|GRID.npy: ordinary, simple or universal kriging (with a
// coordinate or external drift) of scattered samples
// (CSV or GEO-EAS) onto a regular grid, with the kriging variance as a second grid, the
// variogram given or fitted, and a summary of the solver's numerical health.
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <vector>

#include "base/output_file.h"
#include "base/parallel_for.h"
#include "cli/command.h"
#include "cli/krige_options.h"
#include "cli/output_options.h"
#include "cli/process_ranks.h"
#include "cli/progress_bar.h"
#include "cli/shared_grids.h"
#include "geostat/cross_validation.h"
#include "geostat/grid_writer.h"
#include "geostat/krige_grid.h"
#include "geostat/variogram_fit.h"
#include "sources/volume_source.h"

namespace voxlink::cli {
namespace {

using namespace voxlink::geostat;

struct KrigeArgs {
  std::string input, output, varianceOutput;
  std::string xColumn = "X", yColumn = "Y", zColumn, valueColumn;
  std::string variogram, fit, kind = "ok", type = "f64";
  double nu = 0.5, mean = NAN, maxDistance = INFINITY, mergeDistance = -1, noData = NAN,
         maxCondition = 1e12;
  bool fixNuggetZero = false, crossValidate = false;
  size_t neighbours = 0;
  unsigned threads = 0;
  std::string dims, origin, spacing, anisotropy;
  std::string drift = "none", externalDrift, externalDriftGrid;
  OutputOptions out;
};

// The external drift at every node: a dense grid file (any format `convert` reads) with the
// krige grid's dims, read as doubles, x fastest; every value finite.
Result<std::vector<double>> readDriftGrid(const std::string& path, const GridSpec& grid) {
  VOXLINK_ASSIGN_OR_RETURN(auto source, sources::openVolume(path));
  const auto& dims = source->info().dims;
  if (dims != grid.dims)
    return makeError(ErrorCode::kInvalidArgument, path, ": --external-drift-grid is ", dims[0],
                     " x ", dims[1], " x ", dims[2], ", the krige grid ", grid.dims[0], " x ",
                     grid.dims[1], " x ", grid.dims[2]);
  VOXLINK_ASSIGN_OR_RETURN(const std::vector<uint8_t> bytes, sources::readAll(*source));
  std::vector<double> out(grid.nodeCount());
  dispatchScalar(source->info().type, [&](auto zero) {
    using T = decltype(zero);
    for (size_t i = 0; i < out.size(); ++i) {
      T v;
      std::memcpy(&v, bytes.data() + i * sizeof(T), sizeof(T));
      out[i] = static_cast<double>(v);
    }
  });
  for (size_t i = 0; i < out.size(); ++i)
    if (!std::isfinite(out[i]))
      return makeError(ErrorCode::kNonFinite, path, ": --external-drift-grid value at node ", i,
                       " (x ", i % grid.dims[0], ", y ", i / grid.dims[0] % grid.dims[1], ", z ",
                       i / grid.sliceNodes(), ") is not finite");
  return out;
}

Result<GridSpec> gridFromArgs(const KrigeArgs& a, const PointSet& points) {
  const size_t axes = points.dimension;
  GridSpec grid;
  Point3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (const Point3& p : points.coords)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  std::vector<double> dims, origin, spacing;
  if (!a.dims.empty()) {
    VOXLINK_ASSIGN_OR_RETURN(dims, parseNumberList("--dims", a.dims, axes, axes));
  }
  if (!a.origin.empty()) {
    VOXLINK_ASSIGN_OR_RETURN(origin, parseNumberList("--origin", a.origin, axes, axes));
  }
  if (!a.spacing.empty()) {
    VOXLINK_ASSIGN_OR_RETURN(spacing, parseNumberList("--spacing", a.spacing, axes, axes));
  }
  if (dims.empty() && spacing.empty())
    return makeError(ErrorCode::kInvalidArgument,
                     "krige: give --dims or --spacing (the grid covers the samples' bounding box "
                     "unless --origin is given)");
  for (size_t i = 0; i < axes; ++i) {
    grid.origin[i] = origin.empty() ? lo[i] : origin[i];
    if (!dims.empty()) {
      if (dims[i] < 1 || dims[i] > 1e6 || dims[i] != std::floor(dims[i]))
        return makeError(ErrorCode::kInvalidArgument, "--dims: axis ", i,
                         " must be an integer in 1..1000000, got ", dims[i]);
      grid.dims[i] = static_cast<uint32_t>(dims[i]);
    }
    if (!spacing.empty()) {
      if (!(spacing[i] > 0))
        return makeError(ErrorCode::kInvalidArgument, "--spacing: axis ", i, " must be > 0");
      grid.spacing[i] = spacing[i];
      if (dims.empty())
        grid.dims[i] =
            static_cast<uint32_t>(std::floor((hi[i] - grid.origin[i]) / spacing[i] + 1e-9)) + 1;
    } else {
      grid.spacing[i] = grid.dims[i] > 1 ? (hi[i] - grid.origin[i]) / (grid.dims[i] - 1) : 1.0;
      if (!(grid.spacing[i] > 0)) grid.spacing[i] = 1.0;
    }
  }
  return grid;
}

std::string variancePath(const std::string& out) {
  const auto dot = out.rfind('.');
  return out.substr(0, dot) + "_variance" + out.substr(dot);
}

// What every rank needs to krige its share, made from the same sample bytes on every rank.
struct KrigeJob {
  std::optional<Kriger> kriger;
  GridSpec grid;
  GridFileInfo info;
  std::vector<double> nodeDrift;
  std::string varianceFile;
};

// Everything before the grid: the samples (parsed from `sampleText`), the variogram, the
// kriger, cross-validation (rank 0), the output names and the grid. Prints on rank 0 only.
Result<KrigeJob> prepareKrige(const KrigeArgs& a, const std::string& sampleText, bool root) {
  KrigeJob job;
  if (a.externalDrift.empty() != a.externalDriftGrid.empty() && !a.output.empty())
    return makeError(ErrorCode::kInvalidArgument,
                     "krige: --external-drift COLUMN and --external-drift-grid FILE "
                     "go together");
  if (!a.externalDriftGrid.empty() && a.externalDrift.empty())
    return makeError(ErrorCode::kInvalidArgument,
                     "krige: --external-drift-grid needs --external-drift COLUMN");
  ColumnSelection columns{a.xColumn, a.yColumn, a.zColumn, a.valueColumn, a.externalDrift};
  auto points = parsePoints(sampleText, a.input, columns);
  if (!points) return points.error();
  for (const auto& note : points->notes) a.out.print("note: %s\n", note.c_str());
  a.out.print("samples: %zu (%d-D)\n", points->size(), points->dimension);

  VariogramParams params;
  if (!a.variogram.empty()) {
    auto parsed = parseVariogram(a.variogram);
    if (!parsed) return parsed.error();
    params = *parsed;
  } else {
    auto p = parseVariogram(a.fit + ":range=1");
    if (!p)
      return makeError(ErrorCode::kInvalidArgument,
                       "krige: give --variogram MODEL or --fit exp|sph|gau|mat");
    auto bins = experimentalVariogram(*points);
    if (!bins) return bins.error();
    auto fitted = fitVariogram(*bins, {p->type, a.nu, !a.fixNuggetZero});
    if (!fitted) return fitted.error();
    params = *fitted;
    a.out.print("experimental variogram: %zu bins; fitted by WLS (pairs/lag^2)\n", bins->size());
  }
  auto variogram = Variogram::make(params);
  if (!variogram) return variogram.error();
  a.out.print("variogram: %s\n", variogram->describe().c_str());

  KrigingOptions options;
  options.kind = a.kind == "sk" ? KrigingKind::kSimple : KrigingKind::kOrdinary;
  options.simpleMean = a.mean;
  options.maxNeighbours = a.neighbours;
  options.maxDistance = a.maxDistance;
  options.mergeDistance = a.mergeDistance;
  options.maxCondition = a.maxCondition;
  options.drift = a.drift == "linear"      ? DriftKind::kLinear
                  : a.drift == "quadratic" ? DriftKind::kQuadratic
                                           : DriftKind::kNone;
  options.externalDrift = !a.externalDrift.empty();
  if (!a.anisotropy.empty()) {
    auto anis = parseNumberList("--anisotropy", a.anisotropy, 2, 2);
    if (!anis) return anis.error();
    options.anisotropyAngle = (*anis)[0];
    options.anisotropyRatio = (*anis)[1];
  }
  auto kriger = Kriger::make(*points, *variogram, options);
  if (!kriger) return kriger.error();
  if (kriger->driftBasis().terms() > 1) {
    std::string what = a.drift == "none" ? "" : a.drift;
    if (!a.externalDrift.empty())
      what += cat(what.empty() ? "" : " + ", "external '", a.externalDrift, "'");
    a.out.print("drift: %s (%zu terms, constant included)\n", what.c_str(),
                kriger->driftBasis().terms());
  }
  if (kriger->mergedSamples())
    a.out.print("merged: %zu samples closer than %g to another (largest value spread %g)\n",
                kriger->mergedSamples(), kriger->options().mergeDistance,
                kriger->largestMergedSpread());
  if (a.crossValidate && root) {
    auto cv = leaveOneOut(*kriger);
    if (!cv) return cv.error();
    a.out.print(
        "leave-one-out: %zu samples, mean error %.6g, RMSE %.6g, mean standardized squared error "
        "%.4f, r %.4f\n",
        cv->evaluated, cv->meanError, cv->rmse, cv->meanStandardizedSquaredError, cv->correlation);
  }
  if (a.output.empty()) return job;
  // Every file the two grids go to (an .nhdr's .raw too) must spare the input and each other:
  // `-o s.nhdr` over an input named s.raw, or the variance given the values' name, replaced
  // data without a word.
  const std::string varianceFile =
      a.varianceOutput.empty() ? variancePath(a.output) : a.varianceOutput;
  std::vector<std::string> written;
  for (const std::string& out : {a.output, varianceFile})
    for (const std::string& file : GridWriter::filesOf(out)) {
      if (Status s = base::checkOutputTarget(file, {a.input}); !s) return s;
      for (const std::string& other : written)
        if (std::filesystem::weakly_canonical(other) == std::filesystem::weakly_canonical(file))
          return makeError(ErrorCode::kInvalidArgument, file,
                           ": the values and the kriging variance would both be "
                           "written here (give --variance-output another name)");
      written.push_back(file);
    }

  auto grid = gridFromArgs(a, *points);
  if (!grid) return grid.error();
  GridFileInfo info{grid->dims, grid->origin, grid->spacing,
                    a.type == "f32" ? ScalarType::kF32 : ScalarType::kF64};
  std::vector<double> nodeDrift;
  if (options.externalDrift) {
    auto read = readDriftGrid(a.externalDriftGrid, *grid);
    if (!read) return read.error();
    nodeDrift = std::move(*read);
  }
  job.kriger.emplace(std::move(*kriger));
  job.grid = *grid;
  job.info = info;
  job.nodeDrift = std::move(nodeDrift);
  job.varianceFile = varianceFile;
  return job;
}

int runKrige(KrigeArgs a) {
  // On MPI ranks (docs/scale.md) rank 0 reads the samples and broadcasts them once; every rank
  // then makes the same kriger and krige its share of the grid's nodes.
  base::RankGroup& ranks = processRanks();
  const bool root = ranks.rank() == 0;
  if (!root) a.out.quiet = true;
  std::string sampleText;
  Status read;
  if (root) {
    auto text = readSampleFile(a.input);
    if (text)
      sampleText = std::move(*text);
    else
      read = text.status();
  }
  if (Status all = base::agree(ranks, read); !all) return reportOnRankZero(all);
  if (ranks.size() > 1) ranks.broadcast(sampleText, 0);
  auto job = prepareKrige(a, sampleText, root);
  if (Status all = base::agree(ranks, job.status()); !all) return reportOnRankZero(all);
  if (a.output.empty()) return 0;
  const GridSpec& grid = job->grid;
  auto grids = SharedGrids::open(ranks, {a.output, job->varianceFile}, job->info);
  if (!grids) return reportOnRankZero(grids.status());
  GridKrigingOptions gridOptions;
  gridOptions.threads = a.threads;
  gridOptions.noData = a.noData;
  gridOptions.externalDrift = job->nodeDrift.empty() ? nullptr : job->nodeDrift.data();
  ProgressBar bar(a.out.showProgress());
  uint64_t done = 0;
  const GridPart part{static_cast<uint32_t>(ranks.rank()), static_cast<uint32_t>(ranks.size())};
  auto summary = krigeGridPart(
      *job->kriger, grid, part,
      [&](uint64_t first, uint64_t nodes, const double* v, const double* s) -> Status {
        VOXLINK_RETURN_IF_ERROR((*grids)[0].write(first, nodes, v));
        done += nodes;
        bar.update(double(done) * ranks.size() / double(grid.nodeCount()), "krige");
        return (*grids)[1].write(first, nodes, s);
      },
      gridOptions);
  bar.finish();
  if (Status all = grids->finish(summary.status()); !all) return reportOnRankZero(all);
  // The summary of every rank's share, and each rank's peak memory.
  struct RankReport {
    KrigingSummary summary;
    double peakMiB;
  };
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);  // ru_maxrss: KiB on Linux
  const RankReport mine{*summary, usage.ru_maxrss / 1024.0};
  std::vector<RankReport> all(static_cast<size_t>(ranks.size()));
  ranks.allGather(&mine, sizeof mine, all.data());
  if (!root) return 0;
  KrigingSummary total;
  std::string peaks;
  for (const RankReport& r : all) {
    total.add(r.summary);
    peaks += cat(peaks.empty() ? "" : ", ", static_cast<long>(std::lround(r.peakMiB)));
  }
  a.out.print("grid: %u x %u x %u, origin (%g, %g, %g), spacing (%g, %g, %g)\n%s", grid.dims[0],
              grid.dims[1], grid.dims[2], grid.origin[0], grid.origin[1], grid.origin[2],
              grid.spacing[0], grid.spacing[1], grid.spacing[2], total.text().c_str());
  if (ranks.size() > 1)
    a.out.print("ranks: %d; peak memory per rank: %s MiB (resident)\n", ranks.size(),
                peaks.c_str());
  else
    a.out.print("peak memory: %s MiB (resident)\n", peaks.c_str());
  a.out.print("wrote: %s (values), %s (kriging variance)\n", a.output.c_str(),
              job->varianceFile.c_str());
  return 0;
}

}  // namespace

CommandRunner addKrigeCommand(CLI::App& app) {
  auto a = std::make_shared<KrigeArgs>();
  auto* cmd = app.add_subcommand(
      "krige", "Krige scattered samples (CSV or GEO-EAS) onto a grid, with kriging variance");
  cmd->add_option("samples", a->input, "CSV with a header row, or GEO-EAS point file")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option(
      "-o,--output", a->output,
      "Grid file: NAME.nhdr (raw + NRRD header) or NAME.npy; omit to only fit/cross-validate");
  cmd->add_option("--variance-output", a->varianceOutput,
                  "Kriging variance grid (default: NAME_variance.nhdr/.npy)");
  cmd->add_option("--x", a->xColumn, "x column name")->capture_default_str();
  cmd->add_option("--y", a->yColumn, "y column name")->capture_default_str();
  cmd->add_option("--z", a->zColumn, "z column name (omit for 2-D samples)");
  cmd->add_option("--value", a->valueColumn, "value column name")->required();
  cmd->add_option("--variogram", a->variogram,
                  "Model, e.g. sph:nugget=0.1,psill=0.9,range=40 (exp|sph|gau|mat; range = "
                  "practical range; mat takes nu=)");
  cmd->add_option("--fit", a->fit,
                  "Fit this model type to the experimental variogram instead (exp|sph|gau|mat)");
  cmd->add_option("--nu", a->nu, "Matern smoothness for --fit mat")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_flag("--no-nugget", a->fixNuggetZero, "With --fit: keep the nugget at 0");
  cmd->add_option("--kind", a->kind, "ok (ordinary) or sk (simple, needs --mean)")
      ->check(CLI::IsMember({"ok", "sk"}))
      ->capture_default_str();
  cmd->add_option("--mean", a->mean, "Known mean for simple kriging")->check(finiteNumber());
  cmd->add_option("-k,--neighbours", a->neighbours,
                  "Nearest samples per node (0: all, global kriging)")
      ->capture_default_str();
  cmd->add_option("--max-distance", a->maxDistance, "Search radius (default: unlimited)");
  cmd->add_option("--merge-distance", a->mergeDistance,
                  "Merge samples closer than this (default 1e-9 x bounding-box diagonal)")
      ->check(finiteNumber());
  cmd->add_option("--anisotropy", a->anisotropy,
                  "ANGLE,RATIO: the range holds along ANGLE degrees clockwise from +y, RATIO "
                  "(0..1] times it across (gstat's anis); --max-distance is along the range");
  cmd->add_option("--drift", a->drift,
                  "Universal kriging: a trend in the coordinates, none|linear|quadratic (gstat's "
                  "V ~ x + y and V ~ x + y + I(x^2) + I(x*y) + I(y^2)); needs --kind ok")
      ->check(CLI::IsMember({"none", "linear", "quadratic"}))
      ->capture_default_str();
  cmd->add_option("--external-drift", a->externalDrift,
                  "Kriging with external drift: this sample column is a drift term (gstat's "
                  "V ~ U); rows missing it are skipped. Needs --external-drift-grid");
  cmd->add_option("--external-drift-grid", a->externalDriftGrid,
                  "The external drift at every node: a grid file (.nhdr, .npy, ...) with the "
                  "krige grid's dims, x fastest")
      ->check(CLI::ExistingFile);
  cmd->add_option("--max-condition", a->maxCondition,
                  "Regularize systems whose condition estimate exceeds this")
      ->capture_default_str();
  cmd->add_option("--dims", a->dims, "Grid nodes per axis, e.g. 260,300");
  cmd->add_option("--origin", a->origin,
                  "Coordinates of the first node (default: samples' minimum)");
  cmd->add_option("--spacing", a->spacing,
                  "Node spacing per axis (default: bounding box / (dims - 1))");
  cmd->add_option("--type", a->type, "Stored value type")
      ->check(CLI::IsMember({"f64", "f32"}))
      ->capture_default_str();
  cmd->add_option("--nodata", a->noData,
                  "Value written where no sample is within --max-distance (default NaN)");
  cmd->add_flag("--cross-validate", a->crossValidate, "Print leave-one-out statistics");
  addThreadsOption(cmd, a->threads);
  a->out.add(cmd, true);
  return [a] {
    const base::ThreadLimit limit(a->threads);  // every parallel path, for the whole run
    return runKrige(*a);
  };
}

}  // namespace voxlink::cli
