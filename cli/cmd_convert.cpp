// SPDX-License-Identifier: BSD-3-Clause
// voxlink convert INPUT -o OUT.vxl --threshold 60: pre-classify a dense volume and write a
// VoxLink file, with a progress bar and a one-line summary of size, speed and error. Under
// mpirun/srun the ranks share the volume; --batch LIST --out-dir DIR converts many files.
#include <cstdio>
#include <thread>

#include "base/output_file.h"
#include "base/parallel_for.h"
#include "cli/command.h"
#include "cli/convert_batch.h"
#include "cli/output_options.h"
#include "cli/printable_message.h"
#include "cli/process_ranks.h"
#include "cli/progress_bar.h"
#include "cli/source_options.h"
#include "convert/converter.h"
#include "convert/moments.h"
#include "tf/transfer_function.h"

namespace voxlink::cli {
namespace {

struct ConvertArgs {
  std::string input, output;
  SourceArgs source;
  std::vector<std::string> thresholds;
  std::string tfPath;
  std::vector<double> keepOutside;
  std::optional<double> mean, sigma;
  bool standardize = false;
  bool keepAll = false;
  uint32_t brick = 8;
  std::string axis = "z";
  std::string valueType;
  double errorBound = 0;
  unsigned threads = 0;
  uint32_t slab = 64;
  OutputOptions out;
  std::string batch, outDir;  // --batch LIST --out-dir DIR
  bool resume = false;
};

Result<convert::Classification> classificationFrom(const ConvertArgs& a) {
  const int given = !a.thresholds.empty() + !a.tfPath.empty() + !a.keepOutside.empty() + a.keepAll;
  if (given == 0)
    return makeError(ErrorCode::kInvalidArgument, a.input,
                     ": say what to keep: --threshold LO[,HI], --tf TF.json, --keep-outside LO,HI "
                     "or --keep-all");
  if (given > 1)
    return makeError(ErrorCode::kInvalidArgument,
                     "give only one of --threshold, --tf, --keep-outside, --keep-all");
  if (!a.thresholds.empty()) return convert::thresholdClassification(a.thresholds);
  if (!a.tfPath.empty()) {
    VOXLINK_ASSIGN_OR_RETURN(tf::TransferFunction tf, tf::loadTransferFunction(a.tfPath));
    return convert::tfClassification(tf);
  }
  if (!a.keepOutside.empty())
    return convert::keepOutsideClassification(a.keepOutside[0], a.keepOutside[1], a.mean, a.sigma);
  return convert::keepAllClassification();
}

std::string humanCount(uint64_t v) {
  const std::string digits = std::to_string(v);
  std::string out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

// The relative error too when it exceeds f32 rounding (2^-24): an --error-bound that let small
// values go to 0 has a max abs error that looks small next to the large values (rel 1).
std::string relativeErrorNote(double maxRelError) {
  if (!(maxRelError > 0x1p-24)) return "";
  char text[48];
  std::snprintf(text, sizeof text, " (max rel error %.3g)", maxRelError);
  return text;
}

// An input opened and the options of its conversion, printing nothing but --standardize's
// measurement (when `announce`). `ranks` null: this process alone (every file of a batch); else
// the ranks that share the volume.
struct Prepared {
  std::unique_ptr<sources::VolumeSource> source;
  convert::ConvertOptions options;
};
Result<Prepared> prepareFile(const ConvertArgs& a, const std::string& input,
                             const std::string& output, base::RankGroup* ranks, ProgressBar* bar,
                             bool announce) {
  VOXLINK_RETURN_IF_ERROR(base::checkOutputTarget(output, {input}));
  VOXLINK_ASSIGN_OR_RETURN(sources::OpenOptions open, toOpenOptions(a.source));
  VOXLINK_ASSIGN_OR_RETURN(std::unique_ptr<sources::VolumeSource> source,
                           sources::openVolume(input, open));
  VOXLINK_RETURN_IF_ERROR(base::checkOutputTarget(output, input, source->info().files));
  ConvertArgs args = a;
  if (a.standardize) {
    if (a.keepOutside.empty() || a.mean || a.sigma)
      return makeError(ErrorCode::kInvalidArgument,
                       "--standardize goes with --keep-outside and without --mean/--sigma");
    convert::PassProgress momentsProgress;
    if (bar) momentsProgress = bar->callback();
    VOXLINK_ASSIGN_OR_RETURN(convert::Moments moments,
                             convert::measureMoments(*source, a.slab, momentsProgress));
    if (!(moments.sigma > 0))
      return makeError(ErrorCode::kInvalidArgument, input, ": data: every value is ", moments.mean,
                       "; sigma is 0, nothing to standardize");
    if (announce)
      a.out.print("%s: measured mean %.9g, sigma %.9g over %llu voxels (range [%g, %g])\n",
                  input.c_str(), moments.mean, moments.sigma, (unsigned long long)moments.count,
                  moments.min, moments.max);
    args.mean = moments.mean;
    args.sigma = moments.sigma;
  }
  VOXLINK_ASSIGN_OR_RETURN(convert::Classification classification, classificationFrom(args));
  convert::ConvertOptions options;
  options.brickSize = a.brick;
  options.axis = static_cast<format::Axis>(a.axis[0] - 'x');
  options.classification = classification;
  options.threads = a.threads;
  options.slabSlices = a.slab;
  options.errorBound = a.errorBound;
  options.sourceOptions = open;
  options.ranks = ranks;
  if (!a.valueType.empty()) options.storedType = parseStoredName(a.valueType);
  if (bar) options.progress = bar->callback();
  return Prepared{std::move(source), std::move(options)};
}

int runConvert(const ConvertArgs& a) {
  const bool batch = !a.batch.empty();
  if (batch == !a.input.empty() || batch == !a.output.empty() || batch == a.outDir.empty() ||
      (a.resume && !batch))
    return reportOnRankZero(
        makeError(ErrorCode::kInvalidArgument,
                  "give either INPUT -o OUTPUT, or --batch LIST --out-dir DIR [--resume]"));
  if (batch)
    return runBatch(a.batch, a.outDir, a.resume,
                    [&a](const std::string& input,
                         const std::string& output) -> Result<convert::ConvertSummary> {
                      VOXLINK_ASSIGN_OR_RETURN(
                          Prepared p, prepareFile(a, input, output, nullptr, nullptr, false));
                      return convert::convertVolume(*p.source, p.options, output);
                    });
  // Errors before the conversion are agreed too: a rank that cannot open the input must not
  // leave the others waiting for it.
  base::RankGroup& ranks = processRanks();
  const bool root = ranks.rank() == 0;
  ProgressBar bar(root && a.out.showProgress());
  auto prepared = prepareFile(a, a.input, a.output, &ranks, &bar, root);
  if (Status all = base::agree(ranks, prepared.status()); !all) return reportOnRankZero(all);
  // convertVolume agrees on its errors itself.
  auto summary = convert::convertVolume(*prepared->source, prepared->options, a.output);
  bar.finish();
  if (!summary) return reportOnRankZero(summary.status());
  if (!root) return 0;
  const convert::ConvertSummary& s = *summary;
  const sources::VolumeInfo& info = prepared->source->info();
  const double denseBytes = double(info.voxelCount()) * scalarSize(info.type);
  a.out.print(
      "%s: %s of %s voxels (%.2f%%) in %s of %s bricks (%.1f%%) | %.2f MB, %.3f B/voxel, %.1fx "
      "smaller than the dense %s source | values %s, max abs error %g%s | gradients polar16, "
      "error mean %.3f max %.3f deg (%s sampled) | %.2f s (classify %.2f, write %.2f)\n",
      a.output.c_str(), humanCount(s.voxels).c_str(), humanCount(s.sourceVoxels).c_str(),
      100.0 * s.voxels / double(s.sourceVoxels), humanCount(s.occupiedBricks).c_str(),
      humanCount(s.bricks).c_str(), 100.0 * s.occupiedBricks / double(s.bricks), s.bytes / 1e6,
      s.voxels ? double(s.bytes) / s.voxels : 0.0, denseBytes / s.bytes,
      std::string(scalarName(info.type)).c_str(), std::string(storedName(s.storedType)).c_str(),
      s.valueMaxAbsError, relativeErrorNote(s.valueMaxRelError).c_str(), s.gradientMeanErrorDeg,
      s.gradientMaxErrorDeg, humanCount(s.gradientSamples).c_str(), s.seconds, s.countSeconds,
      s.writeSeconds);
  for (const std::string& note : info.notes)
    a.out.print("  note: %s\n", printableMessage(note).c_str());
  return 0;
}

}  // namespace

CommandRunner addConvertCommand(CLI::App& app) {
  auto a = std::make_shared<ConvertArgs>();
  auto* cmd = app.add_subcommand("convert", "Pre-classify a dense volume and write a VoxLink file");
  cmd->add_option("input", a->input,
                  "Dense volume: NRRD, MetaImage, NIfTI, DICOM folder, image stack, VDB, raw, ...");
  cmd->add_option("-o,--output", a->output, "Output VoxLink file (.vxl)");
  cmd->add_option("--batch", a->batch,
                  "Convert every input listed in this file (one a line; relative to its folder)");
  cmd->add_option("--out-dir", a->outDir, "With --batch: folder for the outputs (NAME.vxl)");
  cmd->add_flag("--resume", a->resume, "With --batch: skip outputs that exist and validate");
  addSourceOptions(*cmd, a->source);
  auto* keep = cmd->add_option_group("classification", "What to keep (exactly one)");
  keep->add_option("--threshold", a->thresholds,
                   "Keep values >= LO, or in [LO,HI]; repeat for a union")
      ->allow_extra_args(false);
  keep->add_option("--tf", a->tfPath, "Keep values the transfer function (JSON) gives opacity > 0")
      ->check(CLI::ExistingFile);
  keep->add_option("--keep-outside", a->keepOutside, "Keep values outside [LO,HI], e.g. -1.96,1.96")
      ->delimiter(',')
      ->expected(2)
      ->check(finiteNumber());
  keep->add_flag("--keep-all", a->keepAll, "Keep every voxel");
  cmd->add_option("--mean", a->mean,
                  "With --keep-outside: standardize z = (v - mean) / sigma first")
      ->check(finiteNumber());
  cmd->add_option("--sigma", a->sigma, "With --keep-outside: see --mean")->check(finiteNumber());
  cmd->add_flag("--standardize", a->standardize,
                "With --keep-outside: measure mean and sigma of the volume first");
  cmd->add_option(
         "--brick", a->brick,
         "Brick edge in voxels (8: most compact for sparse scans; 8 and 16 render equally fast)")
      ->check(CLI::IsMember({4, 8, 16, 32}))
      ->capture_default_str();
  cmd->add_option("--axis", a->axis, "Predominant axis: rows of voxels run along it")
      ->check(CLI::IsMember({"x", "y", "z"}))
      ->capture_default_str();
  cmd->add_option("--value-type", a->valueType, "Stored value type (default: smallest lossless)")
      ->check(CLI::IsMember({"u8", "u16", "f16", "f32"}));
  cmd->add_option("--error-bound", a->errorBound,
                  "Largest absolute value error allowed; picks the smallest type within it")
      ->check(finiteNumber());
  addThreadsOption(cmd, a->threads);
  cmd->add_option("--slab", a->slab, "Slices per slab (memory bound; output does not depend on it)")
      ->capture_default_str();
  a->out.add(cmd, true);
  return [a] {
    const base::ThreadLimit limit(a->threads);  // every parallel path, for the whole run
    return runConvert(*a);
  };
}

}  // namespace voxlink::cli
