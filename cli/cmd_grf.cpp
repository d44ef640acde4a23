// voxlink grf --dims X,Y,Z --variogram MODEL -o FIELD.nhdr|FIELD.npy: an unconditional
// Gaussian random field (N(0,1) for a sill of 1) on a voxel grid, generated slab by slab with
// bounded memory, and its empirical statistics against the model.
#include <cmath>
#include <cstdio>

#include "cli/command.h"
#include "cli/krige_options.h"
#include "cli/output_options.h"
#include "cli/progress_bar.h"
#include "format/parallel_for.h"
#include "geostat/field_statistics.h"
#include "geostat/grf.h"
#include "geostat/grid_writer.h"

namespace voxlink::cli {
namespace {

using namespace voxlink::kriging;

struct GrfArgs {
  std::string output, dims, variogram = "exp:range=32", type = "f64";
  uint64_t seed = 1;
  double mean = 0;
  unsigned threads = 0;
  bool stats = false;
  OutputOptions out;
};

int runGrf(const GrfArgs& a) {
  auto dims = parseNumberList("--dims", a.dims, 3, 3);
  if (!dims) return reportError(dims.error());
  GrfSpec spec;
  for (int i = 0; i < 3; ++i) {
    if ((*dims)[i] < 1 || (*dims)[i] != std::floor((*dims)[i]) || (*dims)[i] > kMaxGrfAxis)
      return reportError(makeError(ErrorCode::kInvalidArgument, "--dims: axis ", i,
                                   " must be an integer in 1..", kMaxGrfAxis));
    spec.dims[i] = static_cast<uint32_t>((*dims)[i]);
  }
  auto model = parseVariogram(a.variogram);
  if (!model) return reportError(model.error());
  spec.model = *model;
  spec.seed = a.seed;
  spec.mean = a.mean;
  spec.threads = a.threads;
  auto variogram = Variogram::make(spec.model);
  if (!variogram) return reportError(variogram.error());
  std::unique_ptr<GridWriter> writer;
  if (!a.output.empty()) {
    GridFileInfo info{
        spec.dims, {0, 0, 0}, {1, 1, 1}, a.type == "f32" ? ScalarType::kF32 : ScalarType::kF64};
    auto w = GridWriter::create(a.output, info);
    if (!w) return reportError(w.error());
    writer = std::move(*w);
  }
  std::vector<uint32_t> lags;
  for (uint32_t h = 1; h <= 64; h *= 2) lags.push_back(h);
  FieldStatistics stats(spec.dims, lags, a.mean - 1.96 * std::sqrt(variogram->sill()),
                        a.mean + 1.96 * std::sqrt(variogram->sill()));
  ProgressBar bar(a.out.showProgress());
  auto report = generateGrf(spec, [&](uint32_t z0, uint32_t count, const double* slab) -> Status {
    bar.update(double(z0 + count) / spec.dims[2], "field");
    if (a.stats) stats.add(z0, count, slab);
    return writer ? writer->append(count, slab) : Status::ok();
  });
  bar.finish();
  if (!report) return reportError(report.error());
  if (writer) {
    if (auto st = writer->finish(); !st) return reportError(st);
  }
  a.out.print("field: %u x %u x %u, %s, mean %g, seed %llu\n%s", spec.dims[0], spec.dims[1],
              spec.dims[2], variogram->describe().c_str(), a.mean,
              static_cast<unsigned long long>(a.seed), report->text().c_str());
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
  if (writer) a.out.print("wrote: %s\n", a.output.c_str());
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
  addThreadsOption(cmd, a->threads);
  a->out.add(cmd, true);
  cmd->add_flag("--stats", a->stats,
                "Print empirical mean, sigma, 95 % interval exceedance and axis variograms");
  return [a] {
    const format::ThreadLimit limit(a->threads);  // every parallel path, for the whole run
    return runGrf(*a);
  };
}

}  // namespace voxlink::cli
