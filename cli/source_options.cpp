// SPDX-License-Identifier: BSD-3-Clause
#include "cli/source_options.h"

namespace voxlink::cli {

void addSourceOptions(CLI::App& cmd, SourceArgs& args) {
  cmd.add_option("--dims", args.dims, "Raw input: voxels along x,y,z")->delimiter(',')->expected(3);
  cmd.add_option("--type", args.type,
                 "Raw input: element type (u8, i8, u16, i16, u32, i32, f32, f64)");
  cmd.add_option("--endian", args.endian, "Raw input: byte order")
      ->check(CLI::IsMember({"little", "big"}));
  cmd.add_option("--header-bytes", args.headerBytes, "Raw input: bytes to skip before the data");
  cmd.add_option("--spacing", args.spacing, "Voxel size along x,y,z (overrides the file's)")
      ->delimiter(',')
      ->expected(3);
  cmd.add_option("--vdb-grid", args.vdbGrid,
                 ".vdb input: the grid to read (default: the first float grid)");
  cmd.add_option(
      "--variable", args.variable,
      "GSLIB/GEO-EAS input: the column to read; .vti: the point data array (default: the first)");
  cmd.add_option("--series", args.dicomSeries,
                 "DICOM folder with several series: SeriesInstanceUID or index from "
                 "`voxlink dicom list`");
  cmd.add_option(
      "--format", args.format, "Force a reader: " + [] {
        std::string names;
        for (const std::string& n : sources::readerNames())
          names += (names.empty() ? "" : ", ") + n;
        return names;
      }());
}

Result<sources::OpenOptions> toOpenOptions(const SourceArgs& args) {
  sources::OpenOptions o;
  if (!args.dims.empty())
    o.dims = std::array<uint32_t, 3>{args.dims[0], args.dims[1], args.dims[2]};
  if (!args.type.empty()) {
    auto type = parseScalarName(args.type);
    if (!type)
      return makeError(ErrorCode::kInvalidArgument, "--type ", args.type,
                       ": expected u8, i8, u16, i16, u32, i32, f32 or f64");
    o.type = *type;
  }
  o.endian = args.endian == "big" ? sources::Endian::kBig : sources::Endian::kLittle;
  o.headerBytes = args.headerBytes;
  if (!args.spacing.empty()) {
    for (double s : args.spacing)
      if (!(s > 0 && std::isfinite(s)))
        return makeError(ErrorCode::kInvalidArgument, "--spacing: ", s,
                         " is not a finite value > 0");
    o.spacing = std::array<double, 3>{args.spacing[0], args.spacing[1], args.spacing[2]};
  }
  o.format = args.format;
  o.vdbGrid = args.vdbGrid;
  o.variable = args.variable;
  o.dicomSeries = args.dicomSeries;
  return o;
}

}  // namespace voxlink::cli
