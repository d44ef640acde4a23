// SPDX-License-Identifier: BSD-3-Clause
// voxlink stats INPUT: dims, type, spacing, value range, mean and sigma, and a histogram with
// cumulative fractions, to choose a threshold or a transfer function before converting.
#include <cstdio>

#include "base/limits.h"
#include "cli/command.h"
#include "cli/output_options.h"
#include "cli/printable_message.h"
#include "cli/progress_bar.h"
#include "cli/source_options.h"
#include "convert/histogram.h"

namespace voxlink::cli {

CommandRunner addStatsCommand(CLI::App& app) {
  struct Args {
    std::string input;
    SourceArgs source;
    uint32_t bins = 32;
    OutputOptions out;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand(
      "stats", "Value statistics and histogram of a dense volume (to choose a threshold)");
  cmd->add_option("input", a->input, "Dense volume")->required();
  addSourceOptions(*cmd, a->source);
  cmd->add_option("--bins", a->bins, "Histogram bins")
      ->check(CLI::Range(uint32_t{1}, limits::kMaxHistogramBins))
      ->capture_default_str();
  a->out.add(cmd, true);
  return [a] {
    auto open = toOpenOptions(a->source);
    if (!open) return reportError(open.error());
    auto source = sources::openVolume(a->input, *open);
    if (!source) return reportError(source.error());
    const sources::VolumeInfo& info = (*source)->info();
    ProgressBar bar(a->out.showProgress());
    auto h = convert::measureHistogram(**source, a->bins, 64, bar.callback());
    bar.finish();
    if (!h) return reportError(h.error());
    if (a->out.quiet) return 0;
    std::printf("%s: %s, %ux%ux%u %s, spacing %g %g %g\n", a->input.c_str(), info.format.c_str(),
                info.dims[0], info.dims[1], info.dims[2],
                std::string(scalarName(info.type)).c_str(), info.spacing[0], info.spacing[1],
                info.spacing[2]);
    for (const std::string& note : info.notes)
      std::printf("  note: %s\n", printableMessage(note).c_str());
    std::printf("  values [%g, %g], mean %.6g, sigma %.6g\n", h->moments.min, h->moments.max,
                h->moments.mean, h->moments.sigma);
    std::printf("  %-26s %14s %8s %10s\n", "bin", "voxels", "%", ">= bin %");
    const double width = (h->hi - h->lo) / h->counts.size();
    uint64_t above = h->moments.count;
    for (size_t b = 0; b < h->counts.size(); ++b) {
      char range[64];
      std::snprintf(range, sizeof(range), "[%.6g, %.6g)", h->lo + b * width,
                    h->lo + (b + 1) * width);
      std::printf("  %-26s %14llu %8.3f %10.3f\n", range, (unsigned long long)h->counts[b],
                  100.0 * h->counts[b] / h->moments.count, 100.0 * above / h->moments.count);
      above -= h->counts[b];
    }
    return 0;
  };
}

}  // namespace voxlink::cli
