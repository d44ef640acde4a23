// SPDX-License-Identifier: BSD-3-Clause
// The memory footprint report of `voxlink info`: the paper's Table 3 columns, bytes per
// section, and ratios against the dense source. Peer comparisons (OpenVDB) are added by the
// caller, which measures them (format/ links no OpenVDB).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "format/voxlink_file.h"

namespace voxlink::report {

using format::VoxLinkFile;

struct SectionFootprint {
  std::string name;
  uint64_t bytes = 0;
  double bytesPerVoxel = 0;
};

struct PeerFootprint {
  std::string name;    // e.g. "OpenVDB FloatGrid"
  uint64_t bytes = 0;  // measured in memory
  double bytesPerVoxel = 0;
  double seconds = 0;  // time to build it
  std::string note;
};

// What a scene (version 2 file) holds per object kind; the bytes split the file's sections by
// what they serve: the shared brick/row structure, volume samples, surfaces, spheres.
struct SceneFootprint {
  uint64_t volumeVoxels = 0;   // voxels with a volume sample
  uint64_t surfaceVoxels = 0;  // voxels with a surface fragment
  uint64_t sphereVoxels = 0;   // voxels that reference at least one sphere
  std::string surfaceMode;     // format/surface_mode.h's name: mean, planes, triangles
  uint64_t fragments = 0;      // FRAG entries (planes) or TRID references (triangles)
  uint64_t triangles = 0;      // TRIS entries (triangles)
  uint64_t materials = 0, spheres = 0, sphereRefs = 0;
  uint64_t structureBytes = 0;  // BOCC, BRNK, BVOX, ROWS, MASK
  uint64_t volumeBytes = 0;     // VALU, GRAD, VMSK
  uint64_t surfaceBytes = 0;    // SMSK, SURF, MATL, fragment lists (FROF, FRAG, TRID, TRIS)
  uint64_t sphereBytes = 0;     // SPHR, PMSK, SROF, SRID
};

// What the source's reader did to the numbers in the input file before conversion (DICOM
// RescaleSlope/RescaleIntercept or DoseGridScaling), from META's source.rescale: the values
// stored here are in the rescaled units. Slopes and intercepts may vary per slice in the ranges.
struct ReaderRescale {
  std::string field;       // "RescaleSlope/RescaleIntercept", "DoseGridScaling"
  std::string storedType;  // the input file's own type
  double minSlope = 1, maxSlope = 1, minIntercept = 0, maxIntercept = 0;
};

// Where the grid lies in world units: voxel (i, j, k)'s centre is origin + (i, j, k) * spacing,
// and the bounds are the outer faces of the corner voxels (the box the renderer frames).
struct GridPlacement {
  double origin[3] = {0, 0, 0};
  double spacing[3] = {1, 1, 1};
  double worldMin[3] = {0, 0, 0};
  double worldMax[3] = {0, 0, 0};
  char axis = 'z';                    // the slicing axis: rows of voxels run along it
  uint32_t brickGrid[3] = {0, 0, 0};  // bricks along x, y, z
};

struct FootprintReport {
  std::string path;
  uint32_t dims[3] = {0, 0, 0};
  uint32_t brickSize = 0;
  GridPlacement grid;
  uint64_t voxels = 0;
  double occupancy = 0;  // stored voxels / grid voxels
  uint64_t bricks = 0;
  uint64_t bricksOccupied = 0;
  double bricksNonemptyFraction = 0;
  uint64_t bytesTotal = 0;   // the whole file: header, table, padding, every section
  uint64_t packedBytes = 0;  // on disk, when the file is packed (pack/packed_file.h); else 0
  double bytesPerVoxel = 0;
  std::vector<SectionFootprint> sections;
  uint64_t denseSourceBytes = 0;  // dims x source element size
  double ratioVsDense = 0;        // bytesTotal / denseSourceBytes
  std::string valueType;
  std::string sourceType;
  double valueScale = 1, valueOffset = 0;
  double valueErrorBound = 0;   // what the stored type guarantees (0: lossless)
  double valueMaxAbsError = 0;  // measured when the file was written
  double valueMaxRelError = 0;
  std::optional<ReaderRescale> readerRescale;  // absent for inputs the reader did not rescale
  std::optional<PeerFootprint> peer;
  std::optional<SceneFootprint> scene;  // version 2 files
};

FootprintReport computeFootprint(const VoxLinkFile& file);
std::string footprintTable(const FootprintReport& report);
std::string footprintJson(const FootprintReport& report);

}  // namespace voxlink::report
