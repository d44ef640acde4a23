// SPDX-License-Identifier: BSD-3-Clause
// voxlink pack FILE.vxl -o FILE.packed.vxl: every section compressed losslessly, for sharing;
// voxlink unpack PACKED.vxl -o FILE.vxl: the original file again, byte for byte. Every command
// that reads .vxl files reads packed ones too (unpacked in memory).
#include <chrono>
#include <cstdio>

#include "base/limits.h"
#include "base/mapped_file.h"
#include "base/output_file.h"
#include "base/parallel_for.h"
#include "cli/command.h"
#include "cli/output_options.h"
#include "cli/progress_bar.h"
#include "format/validator.h"
#include "pack/open_file.h"
#include "pack/packed_file.h"

namespace voxlink::cli {
namespace {

const char* codecName(pack::SectionCodec codec) {
  switch (codec) {
    case pack::SectionCodec::kStored:
      return "stored";
    case pack::SectionCodec::kZstd:
      return "zstd";
    case pack::SectionCodec::kDeltaZstd:
      return "delta+zstd";
    case pack::SectionCodec::kGradientResidual:
      return "predicted+zstd";
    case pack::SectionCodec::kGradientResidualPortable:
      return "predicted-f32+zstd";
    case pack::SectionCodec::kDerived:
      return "derived";
  }
  return "?";
}

// The input, validated (and unpacked when packed), once the output is known to be writable:
// openValidatedFile() with `progress` hearing the unpacking (when packed) and the validation.
Result<format::VoxLinkFile> openInputFor(const std::string& input, const std::string& output,
                                         const base::ProgressCallback& progress) {
  VOXLINK_RETURN_IF_ERROR(base::checkOutputTarget(output, {input}));
  VOXLINK_ASSIGN_OR_RETURN(base::MappedFile mapped, base::MappedFile::open(input));
  const std::span<const uint8_t> bytes(mapped.data(), mapped.size());
  const bool packed = pack::isPackedFile(bytes);
  Result<format::VoxLinkFile> file = packed
                                         ? pack::unpackFile(bytes, input, limits::kMaxUnpackedBytes,
                                                            0, base::progressPart(progress, 0, 0.5))
                                         : pack::openFile(input);
  if (!file) return file;
  VOXLINK_RETURN_IF_ERROR(
      format::validateFile(*file, base::progressPart(progress, packed ? 0.5 : 0, 1)).status());
  return file;
}

}  // namespace

CommandRunner addPackCommand(CLI::App& app) {
  struct Args {
    std::string path, output;
    int level = 1;
    unsigned threads = 0;
    bool sections = false, fast = false;
    OutputOptions out;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand(
      "pack",
      "Compress a VoxLink file losslessly for storage and sharing (voxlink unpack undoes it)");
  cmd->add_option("file", args->path, "VoxLink file (.vxl)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output, "Packed output (.vxl)")->required();
  cmd->add_option("--level", args->level,
                  "zstd level (1 fastest, 19 smallest: on the 1024^3 CT foot 16 % smaller, 47x "
                  "slower to pack, as fast to load)")
      ->check(CLI::Range(1, 19))
      ->capture_default_str();
  addThreadsOption(cmd, args->threads);
  cmd->add_flag("--fast", args->fast,
                "Do not predict gradients from the values: on CT twice as fast to load, files "
                "about 2.4x as large, not reliably faster to pack (docs/benchmarks.md)");
  cmd->add_flag("--sections", args->sections, "Print each section's size before and after");
  args->out.add(cmd, true);
  return [args] {
    const base::ThreadLimit limit(args->threads);  // every parallel path, for the whole run
    const auto start = std::chrono::steady_clock::now();
    // Validating a fifth of the bar, packing the rest (GRAD's prediction dominates).
    ProgressBar bar(args->out.showProgress());
    const base::ProgressCallback progress = bar.callback();
    auto file = openInputFor(args->path, args->output, base::progressPart(progress, 0, 0.2));
    if (!file) return bar.fail(file.error());
    const double readSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (file->packedBytes() != 0)
      return bar.fail(makeError(ErrorCode::kInvalidArgument, args->path,
                                ": already packed (voxlink unpack gives the original)"));
    auto report = pack::packFile(
        *file, args->output,
        {args->level, args->threads, !args->fast, base::progressPart(progress, 0.2, 1)});
    bar.finish();
    if (!report) return reportError(report.error());
    if (args->out.quiet) return 0;
    if (args->sections) {
      std::printf("%-6s %-15s %14s %14s %8s\n", "section", "codec", "bytes", "packed", "ratio");
      for (const auto& s : report->sections)
        std::printf("%-6.4s  %-15s %14llu %14llu %7.2fx\n",
                    std::string(format::sectionName(s.id)).c_str(), codecName(s.codec),
                    (unsigned long long)s.rawBytes, (unsigned long long)s.packedBytes,
                    s.packedBytes ? double(s.rawBytes) / double(s.packedBytes) : 0.0);
    }
    const double voxels = std::max<double>(1, double(file->voxelCount()));
    std::printf(
        "%s: %.2f MB -> %.2f MB (%.2fx smaller), %.3f B/voxel | packed in %.2f s (%.0f MB/s of "
        "input; %.2f s of it predicting gradients), after reading and validating in %.2f s\n",
        args->output.c_str(), report->inputBytes / 1e6, report->outputBytes / 1e6,
        double(report->inputBytes) / double(report->outputBytes), report->outputBytes / voxels,
        report->packSeconds, report->inputBytes / 1e6 / report->packSeconds, report->predictSeconds,
        readSeconds);
    return 0;
  };
}

CommandRunner addUnpackCommand(CLI::App& app) {
  struct Args {
    std::string path, output;
    unsigned threads = 0;
    OutputOptions out;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("unpack", "Write the original of a packed VoxLink file");
  cmd->add_option("file", args->path, "Packed VoxLink file (.vxl)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output, "Unpacked output (.vxl)")->required();
  addThreadsOption(cmd, args->threads);
  args->out.add(cmd, true);
  return [args] {
    const base::ThreadLimit limit(args->threads);  // every parallel path, for the whole run
    const auto start = std::chrono::steady_clock::now();
    // Unpacking and validating 90 % of the bar, writing the rest.
    ProgressBar bar(args->out.showProgress());
    const base::ProgressCallback progress = bar.callback();
    auto file = openInputFor(args->path, args->output, base::progressPart(progress, 0, 0.9));
    if (!file) return bar.fail(file.error());
    if (file->packedBytes() == 0)
      return bar.fail(makeError(ErrorCode::kInvalidArgument, args->path,
                                ": not a packed file (nothing to unpack)"));
    bar.update(0.9, "writing");
    const Status written = base::writeWholeFile(args->output, file->bytes());
    if (written) bar.update(1.0, "written");
    bar.finish();
    if (!written) return reportError(written);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    args->out.print("%s: %.2f MB from %.2f MB packed, unpacked, validated and written in %.2f s\n",
                    args->output.c_str(), file->fileBytes() / 1e6, file->packedBytes() / 1e6,
                    seconds);
    return 0;
  };
}

}  // namespace voxlink::cli
