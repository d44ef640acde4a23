// SPDX-License-Identifier: BSD-3-Clause
#include "report/footprint.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "format/surface_mode.h"

namespace voxlink::report {

using format::FileHeader;
using format::SectionEntry;
using format::SectionId;
using format::sectionName;
using format::VoxLinkFile;

namespace {

SceneFootprint computeSceneFootprint(const VoxLinkFile& f) {
  const FileHeader& h = f.header();
  SceneFootprint s;
  s.volumeVoxels = h.volumeVoxelCount;
  s.surfaceVoxels = h.surfaceVoxelCount;
  s.materials = h.materialCount;
  s.spheres = h.sphereCount;
  s.sphereRefs = h.sphereRefCount;
  s.sphereVoxels = h.sphereVoxelCount;
  s.surfaceMode = std::string(format::surfaceModeName(f.surfaceMode()));
  s.fragments = h.fragmentCount;
  s.triangles = h.triangleCount;
  for (const SectionEntry& e : f.sectionTable()) {
    switch (static_cast<SectionId>(e.id)) {
      case SectionId::kValues:
      case SectionId::kGradients:
      case SectionId::kVolumeMask:
        s.volumeBytes += e.bytes;
        break;
      case SectionId::kSurface:
      case SectionId::kSurfaceMask:
      case SectionId::kMaterials:
      case SectionId::kFragmentStart:
      case SectionId::kFragments:
      case SectionId::kTriangleRefs:
      case SectionId::kTriangles:
        s.surfaceBytes += e.bytes;
        break;
      case SectionId::kSphereMask:
      case SectionId::kSpheres:
      case SectionId::kSphereRefStart:
      case SectionId::kSphereRefs:
        s.sphereBytes += e.bytes;
        break;
      case SectionId::kMeta:
        break;
      default:
        s.structureBytes += e.bytes;
        break;
    }
  }
  return s;
}

// META's source.rescale, when the converter recorded one; a value of the wrong shape is left
// out (validate checks META's checksum, not its contents).
std::optional<ReaderRescale> readerRescale(const VoxLinkFile& f) {
  const auto meta = nlohmann::json::parse(f.metaJson(), nullptr, false);
  if (!meta.is_object() || !meta.contains("source") || !meta["source"].is_object()) return {};
  const auto& source = meta["source"];
  if (!source.contains("rescale") || !source["rescale"].is_object()) return {};
  const auto& j = source["rescale"];
  const auto pair = [&](const char* key) {
    return j.contains(key) && j[key].is_array() && j[key].size() == 2 && j[key][0].is_number() &&
           j[key][1].is_number();
  };
  if (!j.contains("field") || !j["field"].is_string() || !j.contains("stored_type") ||
      !j["stored_type"].is_string() || !pair("slope") || !pair("intercept"))
    return {};
  return ReaderRescale{j["field"].get<std::string>(),   j["stored_type"].get<std::string>(),
                       j["slope"][0].get<double>(),     j["slope"][1].get<double>(),
                       j["intercept"][0].get<double>(), j["intercept"][1].get<double>()};
}

GridPlacement gridPlacement(const FileHeader& h) {
  GridPlacement g;
  for (int a = 0; a < 3; ++a) {
    g.origin[a] = h.origin[a];
    g.spacing[a] = h.spacing[a];
    g.worldMin[a] = h.origin[a] - 0.5 * h.spacing[a];
    g.worldMax[a] = h.origin[a] + (double(h.dims[a]) - 0.5) * h.spacing[a];
    g.brickGrid[a] = h.brickGrid[a];
  }
  g.axis = static_cast<char>('x' + std::min<int>(h.predominantAxis, 2));
  return g;
}

}  // namespace

FootprintReport computeFootprint(const VoxLinkFile& f) {
  const FileHeader& h = f.header();
  FootprintReport r;
  r.path = f.path();
  for (int a = 0; a < 3; ++a) r.dims[a] = h.dims[a];
  r.brickSize = h.brickSize;
  r.grid = gridPlacement(h);
  r.voxels = h.voxelCount;
  const double gridVoxels = double(h.dims[0]) * h.dims[1] * h.dims[2];
  r.occupancy = r.voxels / gridVoxels;
  r.bricks = f.gridBrickCount();
  r.bricksOccupied = h.occupiedBrickCount;
  r.bricksNonemptyFraction = r.bricks ? double(r.bricksOccupied) / r.bricks : 0.0;
  r.bytesTotal = f.fileBytes();
  r.packedBytes = f.packedBytes();
  r.bytesPerVoxel = r.voxels ? double(r.bytesTotal) / r.voxels : 0.0;
  const double perVoxel = r.voxels ? 1.0 / r.voxels : 0.0;
  uint64_t sectionTotal = 0;
  for (const SectionEntry& e : f.sectionTable()) {
    r.sections.push_back(
        {std::string(sectionName(static_cast<SectionId>(e.id))), e.bytes, e.bytes * perVoxel});
    sectionTotal += e.bytes;
  }
  const uint64_t overhead = r.bytesTotal - sectionTotal;
  r.sections.push_back({"header+table+padding", overhead, overhead * perVoxel});
  r.denseSourceBytes = static_cast<uint64_t>(gridVoxels) * scalarSize(f.sourceType());
  r.ratioVsDense = double(r.bytesTotal) / double(r.denseSourceBytes);
  r.valueType = std::string(storedName(f.valueType()));
  r.sourceType = std::string(scalarName(f.sourceType()));
  r.valueScale = h.valueScale;
  r.valueOffset = h.valueOffset;
  r.valueErrorBound = h.valueErrorBound;
  r.valueMaxAbsError = h.valueMaxAbsError;
  r.valueMaxRelError = h.valueMaxRelError;
  if (f.isScene()) r.scene = computeSceneFootprint(f);
  r.readerRescale = readerRescale(f);
  return r;
}

std::string footprintTable(const FootprintReport& r) {
  std::string out;
  char line[256];
  auto add = [&](const char* fmt, auto... args) {
    std::snprintf(line, sizeof(line), fmt, args...);
    out += line;
  };
  add("%s\n", r.path.c_str());
  add("  %-22s %-16s %-12s %-12s %-11s %-10s\n", "resolution [brick]", "voxels", "non-empty %",
      "bricks %", "total MB", "B/voxel");
  char res[64];
  std::snprintf(res, sizeof(res), "%ux%ux%u [%u]", r.dims[0], r.dims[1], r.dims[2], r.brickSize);
  add("  %-22s %-16llu %-12.3f %-12.2f %-11.2f %-10.3f\n", res, (unsigned long long)r.voxels,
      100.0 * r.occupancy, 100.0 * r.bricksNonemptyFraction, r.bytesTotal / 1e6, r.bytesPerVoxel);
  const GridPlacement& g = r.grid;
  add("  grid: origin (%g, %g, %g), spacing (%g, %g, %g); world bounds (%g, %g, %g) to (%g, %g, "
      "%g)\n",
      g.origin[0], g.origin[1], g.origin[2], g.spacing[0], g.spacing[1], g.spacing[2],
      g.worldMin[0], g.worldMin[1], g.worldMin[2], g.worldMax[0], g.worldMax[1], g.worldMax[2]);
  add("  rows along %c, bricks of %u^3 voxels, %ux%ux%u bricks\n", g.axis, r.brickSize,
      g.brickGrid[0], g.brickGrid[1], g.brickGrid[2]);
  if (r.valueErrorBound == 0 && r.valueMaxAbsError == 0) {
    add("  values %s (source %s), lossless: source = stored * %g + %g\n", r.valueType.c_str(),
        r.sourceType.c_str(), r.valueScale, r.valueOffset);
  } else {
    add("  values %s (source %s): source = stored * %g + %g; error bound %g %s, measured max abs "
        "%g, max rel %g\n",
        r.valueType.c_str(), r.sourceType.c_str(), r.valueScale, r.valueOffset, r.valueErrorBound,
        r.valueMaxAbsError <= r.valueErrorBound ? "met" : "NOT met", r.valueMaxAbsError,
        r.valueMaxRelError);
  }
  if (r.readerRescale) {
    const ReaderRescale& x = *r.readerRescale;
    if (x.minSlope == x.maxSlope && x.minIntercept == x.maxIntercept)
      add("  source values rescaled by the reader (%s): source = file %s * %g + %g\n",
          x.field.c_str(), x.storedType.c_str(), x.minSlope, x.minIntercept);
    else
      add("  source values rescaled by the reader (%s, per slice): source = file %s * slope + "
          "intercept, slopes %g..%g, intercepts %g..%g\n",
          x.field.c_str(), x.storedType.c_str(), x.minSlope, x.maxSlope, x.minIntercept,
          x.maxIntercept);
  }
  add("  %-22s %14s %10s\n", "section", "bytes", "B/voxel");
  for (const SectionFootprint& s : r.sections)
    add("  %-22s %14llu %10.3f\n", s.name.c_str(), (unsigned long long)s.bytes, s.bytesPerVoxel);
  add("  %-22s %14llu %10.3f\n", "total", (unsigned long long)r.bytesTotal, r.bytesPerVoxel);
  if (r.packedBytes)
    add("  %-22s %14llu %10.3f  (%.2fx smaller; the sizes above are unpacked, in memory)\n",
        "packed on disk", (unsigned long long)r.packedBytes,
        r.voxels ? double(r.packedBytes) / r.voxels : 0.0, double(r.bytesTotal) / r.packedBytes);
  if (r.scene) {
    const SceneFootprint& s = *r.scene;
    auto mb = [](uint64_t bytes) { return bytes / 1e6; };
    add("  scene: %llu volume voxels, %llu surface voxels (%llu materials), %llu sphere voxels "
        "(%llu spheres, %llu references)\n",
        (unsigned long long)s.volumeVoxels, (unsigned long long)s.surfaceVoxels,
        (unsigned long long)s.materials, (unsigned long long)s.sphereVoxels,
        (unsigned long long)s.spheres, (unsigned long long)s.sphereRefs);
    if (s.surfaceMode == "planes")
      add("  surface mode planes: %llu fragments, %.3f per surface voxel\n",
          (unsigned long long)s.fragments,
          s.surfaceVoxels ? double(s.fragments) / s.surfaceVoxels : 0.0);
    else if (s.surfaceMode == "triangles")
      add("  surface mode triangles: %llu triangles, %llu references, %.3f per surface voxel\n",
          (unsigned long long)s.triangles, (unsigned long long)s.fragments,
          s.surfaceVoxels ? double(s.fragments) / s.surfaceVoxels : 0.0);
    else
      add("  surface mode mean: one fragment per surface voxel\n");
    add("  by kind: bricks+rows %.3f MB, volume %.3f MB, surfaces %.3f MB, spheres %.3f MB\n",
        mb(s.structureBytes), mb(s.volumeBytes), mb(s.surfaceBytes), mb(s.sphereBytes));
  }
  add("  dense source: %llu bytes; this file is %.2f%% of it (%.1fx smaller)\n",
      (unsigned long long)r.denseSourceBytes, 100.0 * r.ratioVsDense,
      r.ratioVsDense > 0 ? 1.0 / r.ratioVsDense : 0.0);
  if (r.peer) {
    const PeerFootprint& p = *r.peer;
    add("  %s holding the same voxels: %llu bytes (%.3f B/voxel, measured in %.2f s); this file is "
        "%.2fx %s\n",
        p.name.c_str(), (unsigned long long)p.bytes, p.bytesPerVoxel, p.seconds,
        p.bytes ? double(r.bytesTotal) / p.bytes : 0.0, "its size");
    if (!p.note.empty()) add("  (%s)\n", p.note.c_str());
  }
  return out;
}

std::string footprintJson(const FootprintReport& r) {
  nlohmann::ordered_json j;
  j["path"] = r.path;
  j["dims"] = {r.dims[0], r.dims[1], r.dims[2]};
  j["brick_size"] = r.brickSize;
  const GridPlacement& g = r.grid;
  j["origin"] = {g.origin[0], g.origin[1], g.origin[2]};
  j["spacing"] = {g.spacing[0], g.spacing[1], g.spacing[2]};
  j["world_bounds"] = {{"min", {g.worldMin[0], g.worldMin[1], g.worldMin[2]}},
                       {"max", {g.worldMax[0], g.worldMax[1], g.worldMax[2]}}};
  j["axis"] = std::string(1, g.axis);
  j["brick_grid"] = {g.brickGrid[0], g.brickGrid[1], g.brickGrid[2]};
  j["voxels"] = r.voxels;
  j["occupancy"] = r.occupancy;
  j["bricks"] = r.bricks;
  j["bricks_nonempty"] = r.bricksOccupied;
  j["bricks_nonempty_fraction"] = r.bricksNonemptyFraction;
  j["bytes_total"] = r.bytesTotal;
  j["bytes_per_voxel"] = r.bytesPerVoxel;
  j["packed_bytes"] = r.packedBytes;
  j["value_type"] = r.valueType;
  j["source_type"] = r.sourceType;
  j["value_mapping"] = {{"scale", r.valueScale}, {"offset", r.valueOffset}};
  j["value_error"] = {{"bound", r.valueErrorBound},
                      {"bound_met", r.valueMaxAbsError <= r.valueErrorBound},
                      {"max_abs", r.valueMaxAbsError},
                      {"max_rel", r.valueMaxRelError}};
  if (r.readerRescale) {
    const ReaderRescale& x = *r.readerRescale;
    j["reader_rescale"] = {{"field", x.field},
                           {"stored_type", x.storedType},
                           {"slope", {x.minSlope, x.maxSlope}},
                           {"intercept", {x.minIntercept, x.maxIntercept}}};
  }
  nlohmann::ordered_json sections = nlohmann::ordered_json::object();
  for (const SectionFootprint& s : r.sections) sections[s.name] = s.bytes;
  j["sections"] = sections;
  j["dense_source_bytes"] = r.denseSourceBytes;
  j["ratio_vs_dense"] = r.ratioVsDense;
  if (r.scene) {
    const SceneFootprint& s = *r.scene;
    j["scene"] = {{"volume_voxels", s.volumeVoxels}, {"surface_voxels", s.surfaceVoxels},
                  {"sphere_voxels", s.sphereVoxels}, {"surface_mode", s.surfaceMode},
                  {"fragments", s.fragments},        {"triangles", s.triangles},
                  {"materials", s.materials},        {"spheres", s.spheres},
                  {"sphere_refs", s.sphereRefs},     {"structure_bytes", s.structureBytes},
                  {"volume_bytes", s.volumeBytes},   {"surface_bytes", s.surfaceBytes},
                  {"sphere_bytes", s.sphereBytes}};
  }
  if (r.peer) {
    j["peer"] = {{"name", r.peer->name},
                 {"bytes", r.peer->bytes},
                 {"bytes_per_voxel", r.peer->bytesPerVoxel},
                 {"seconds", r.peer->seconds},
                 {"ratio", r.peer->bytes ? double(r.bytesTotal) / r.peer->bytes : 0.0},
                 {"note", r.peer->note}};
  }
  return j.dump(2);
}

}  // namespace voxlink::report
