// SPDX-License-Identifier: BSD-3-Clause
// voxlink dicom list PATH [--json]: the DICOM series under a folder (recursive), so a user can
// pick one for `voxlink convert PATH --series UID|INDEX`.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "cli/output_options.h"
#include "sources/readers/dicom_reader.h"

namespace voxlink::cli {
namespace {

std::string dimsText(const sources::DicomSeriesSummary& s) {
  if (!s.problem.empty()) return "-";
  return cat(s.dims[0], "x", s.dims[1], "x", s.dims[2]);
}

std::string spacingText(const sources::DicomSeriesSummary& s) {
  if (!s.problem.empty()) return "-";
  char text[96];
  std::snprintf(text, sizeof text, "%g x %g x %g", s.spacing[0], s.spacing[1], s.spacing[2]);
  return text;
}

void printTable(const sources::DicomFolderListing& listing) {
  std::printf("%-3s %-8s %-12s %-14s %-7s %-7s %-10s %-24s %s\n", "#", "modality", "dims",
              "spacing (mm)", "files", "images", "MB", "description", "SeriesInstanceUID");
  for (size_t i = 0; i < listing.series.size(); ++i) {
    const sources::DicomSeriesSummary& s = listing.series[i];
    std::printf("%-3zu %-8s %-12s %-14s %-7llu %-7llu %-10.2f %-24s %s\n", i + 1,
                s.modality.c_str(), dimsText(s).c_str(), spacingText(s).c_str(),
                (unsigned long long)s.files, (unsigned long long)s.frames, s.bytes / 1e6,
                s.description.c_str(), s.uid.c_str());
    if (!s.problem.empty()) std::printf("    cannot be read as a volume: %s\n", s.problem.c_str());
  }
  std::printf(
      "%zu series; skipped: %llu files that are not DICOM (DICOMDIR included), %llu "
      "DICOM files without an image\n",
      listing.series.size(), (unsigned long long)listing.otherFiles,
      (unsigned long long)listing.nonImages);
}

std::string listingJson(const sources::DicomFolderListing& listing) {
  nlohmann::ordered_json j;
  nlohmann::ordered_json series = nlohmann::ordered_json::array();
  for (size_t i = 0; i < listing.series.size(); ++i) {
    const sources::DicomSeriesSummary& s = listing.series[i];
    nlohmann::ordered_json e;
    e["index"] = i + 1;
    e["series_instance_uid"] = s.uid;
    e["modality"] = s.modality;
    e["description"] = s.description;
    e["files"] = s.files;
    e["images"] = s.frames;
    e["bytes"] = s.bytes;
    if (s.problem.empty()) {
      e["dims"] = s.dims;
      e["spacing"] = s.spacing;
    } else {
      e["problem"] = s.problem;
    }
    series.push_back(e);
  }
  j["series"] = series;
  j["skipped"] = {{"not_dicom", listing.otherFiles}, {"without_image", listing.nonImages}};
  return j.dump(2);
}

}  // namespace

CommandRunner addDicomCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("dicom", "DICOM folders: list the series they hold");
  cmd->require_subcommand(1);
  auto* list = cmd->add_subcommand(
      "list", "Every series under a folder (recursive): modality, dims, spacing, images, size");
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto out = std::make_shared<OutputOptions>();
  list->add_option("path", *path, "Folder (searched recursively) or one DICOM file")->required();
  list->add_flag("--json", *json, "Print JSON instead of a table");
  out->add(list, false);
  return [path, json, out]() {
    auto listing = sources::listDicomFolder(*path);
    if (!listing) return reportError(listing.error());
    if (out->quiet) return 0;
    if (*json)
      std::printf("%s\n", listingJson(*listing).c_str());
    else
      printTable(*listing);
    return 0;
  };
}

}  // namespace voxlink::cli
