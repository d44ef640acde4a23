// SPDX-License-Identifier: BSD-3-Clause
// voxlink grf --dims X,Y,Z --variogram MODEL -o FIELD.nhdr|FIELD.npy: an unconditional
// Gaussian random field (N(0,1) for a sill of 1) on a voxel grid, generated slab by slab with
// bounded memory, and its empirical statistics against the model.
#include <cmath>
#include <cstdio>
#include <optional>

#include "base/parallel_for.h"
#include "cli/command.h"
#include "cli/krige_options.h"
#include "cli/output_options.h"
#include "cli/process_ranks.h"
#include "cli/progress_bar.h"
#include "cli/shared_grids.h"
#include "geostat/field_statistics.h"
#include "geostat/grf.h"
#include "geostat/grid_writer.h"

namespace voxlink::cli {
namespace {

using namespace voxlink::geostat;

struct GrfArgs {
  std::string output, dims, variogram = "exp:range=32", type = "f64";
  uint64_t seed = 1;
  uint32_t fftSize = 0;
  double mean = 0;
  unsigned threads = 0;
  bool stats = false;
  OutputOptions out;
};

// The field's spec from the options (the same on every rank).
Result<GrfSpec> grfSpec(const GrfArgs& a) {
  VOXLINK_ASSIGN_OR_RETURN(const std::vector<double> dims, parseNumberList("--dims", a.dims, 3, 3));
  GrfSpec spec;
  for (int i = 0; i < 3; ++i) {
    if (dims[i] < 1 || dims[i] != std::floor(dims[i]) || dims[i] > kMaxGrfAxis)
      return makeError(ErrorCode::kInvalidArgument, "--dims: axis ", i,
                       " must be an integer in 1..", kMaxGrfAxis);
    spec.dims[i] = static_cast<uint32_t>(dims[i]);
  }
  VOXLINK_ASSIGN_OR_RETURN(spec.model, parseVariogram(a.variogram));
  spec.seed = a.seed;
  spec.mean = a.mean;
  spec.threads = a.threads;
  spec.fftSize = a.fftSize;
  return spec;
}

int runGrf(GrfArgs a) {
  // On MPI ranks (docs/scale.md) each rank makes its share of the field: the noise is a hash of
  // the seed and the voxel, so the field does not depend on the split.
  base::RankGroup& ranks = processRanks();
  const bool root = ranks.rank() == 0;
  if (!root) a.out.quiet = true;
  auto spec = grfSpec(a);
  if (spec && a.stats && ranks.size() > 1)
    spec = makeError(ErrorCode::kInvalidArgument,
                     "grf: --stats runs in one process (its axis variograms pair voxels across "
                     "the ranks' shares); leave it out under mpirun");
  Result<Variogram> variogram =
      spec ? Variogram::make(spec->model) : Result<Variogram>(spec.status());
  if (!variogram) return reportOnRankZero(variogram.status());
  std::optional<SharedGrids> grids;
  if (!a.output.empty()) {
    GridFileInfo info{
        spec->dims, {0, 0, 0}, {1, 1, 1}, a.type == "f32" ? ScalarType::kF32 : ScalarType::kF64};
    auto opened = SharedGrids::open(ranks, {a.output}, info);
    if (!opened) return reportOnRankZero(opened.status());
    grids.emplace(std::move(*opened));
  }
  std::vector<uint32_t> lags;
  for (uint32_t h = 1; h <= 64; h *= 2) lags.push_back(h);
  FieldStatistics stats(spec->dims, lags, a.mean - 1.96 * std::sqrt(variogram->sill()),
                        a.mean + 1.96 * std::sqrt(variogram->sill()));
  ProgressBar bar(a.out.showProgress());
  const uint64_t sliceVoxels = uint64_t{spec->dims[0]} * spec->dims[1];
  const uint64_t voxels = sliceVoxels * spec->dims[2];
  uint64_t done = 0;
  const GridPart part{static_cast<uint32_t>(ranks.rank()), static_cast<uint32_t>(ranks.size())};
  auto report = generateGrfPart(
      *spec, part,
      [&](uint64_t first, uint64_t count, const double* slab, const double*) -> Status {
        done += count;
        bar.update(double(done) * ranks.size() / double(voxels), "field");
        // One process: whole slices in order, as the statistics want them.
        if (a.stats)
          stats.add(static_cast<uint32_t>(first / sliceVoxels),
                    static_cast<uint32_t>(count / sliceVoxels), slab);
        return grids ? (*grids)[0].write(first, count, slab) : Status::ok();
      });
  bar.finish();
  if (grids) {
    if (Status all = grids->finish(report.status()); !all) return reportOnRankZero(all);
  } else if (Status all = base::agree(ranks, report.status()); !all) {
    return reportOnRankZero(all);
  }
  uint64_t blocks = report->blocks, allBlocks = 0;
  std::vector<uint64_t> each(static_cast<size_t>(ranks.size()));
  ranks.allGather(&blocks, sizeof blocks, each.data());
  for (uint64_t b : each) allBlocks += b;
  report->blocks = allBlocks;
  a.out.print("field: %u x %u x %u, %s, mean %g, seed %llu\n%s", spec->dims[0], spec->dims[1],
              spec->dims[2], variogram->describe().c_str(), a.mean,
              static_cast<unsigned long long>(a.seed), report->text().c_str());
  if (ranks.size() > 1) a.out.print("ranks: %d (times and buffers: rank 0's)\n", ranks.size());
  if (a.stats) {
    a.out.print(
        "empirical: mean %.5f, sigma %.5f, outside mean +- 1.96 sigma_model: %.4f %% (Gaussian: "
        "5.00 %%)\n",
        stats.mean(), stats.sigma(), 100 * stats.outsideFraction());
    a.out.print("%6s %12s %12s %12s %12s\n", "lag", "model", "gamma_x", "gamma_y", "gamma_z");
    for (size_t l = 0; l < lags.size(); ++l)
      a.out.print("%6u %12.5f %12.5f %12.5f %12.5f\n", lags[l], variogram->gamma(lags[l]),
                  stats.gamma(0, l), stats.gamma(1, l), stats.gamma(2, l));
  }
  if (grids) a.out.print("wrote: %s\n", a.output.c_str());
  return 0;
}

}  // namespace

CommandRunner addGrfCommand(CLI::App& app) {
  auto a = std::make_shared<GrfArgs>();
  auto* cmd = app.add_subcommand(
      "grf", "Unconditional Gaussian random field on a voxel grid (FFT, bounded memory)");
  cmd->add_option("--dims", a->dims, "Voxels per axis, e.g. 512,512,512")->required();
  cmd->add_option("--variogram", a->variogram,
                  "Covariance model in voxel units, e.g. exp:psill=1,range=32 (sill 1: N(0,1))")
      ->capture_default_str();
  cmd->add_option("--seed", a->seed, "Random seed")->capture_default_str();
  cmd->add_option("--mean", a->mean, "Field mean")->check(finiteNumber())->capture_default_str();
  cmd->add_option("-o,--output", a->output,
                  "NAME.nhdr (raw + NRRD header) or NAME.npy; omit to only time/measure");
  cmd->add_option("--type", a->type, "Stored value type")
      ->check(CLI::IsMember({"f64", "f32"}))
      ->capture_default_str();
  cmd->add_option("--fft-size", a->fftSize,
                  "FFT block edge in voxels (0: chosen for speed); smaller blocks, more of them, "
                  "for threads and MPI ranks to share. The field changes with it by rounding")
      ->capture_default_str();
  addThreadsOption(cmd, a->threads);
  a->out.add(cmd, true);
  cmd->add_flag("--stats", a->stats,
                "Print empirical mean, sigma, 95 % interval exceedance and axis variograms");
  return [a] {
    const base::ThreadLimit limit(a->threads);  // every parallel path, for the whole run
    return runGrf(*a);
  };
}

}  // namespace voxlink::cli
