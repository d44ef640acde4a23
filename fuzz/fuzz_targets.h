// SPDX-License-Identifier: BSD-3-Clause
// The fuzz entry points: one per input format, each taking the raw fuzz input and returning the
// first error the library reported (Ok when the input was accepted and fully read). libFuzzer
// executables (fuzz/libfuzzer_main.cpp) and the regression tests (tests/fuzz) call the same
// functions, so a kept crash input replays exactly.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "base/error.h"

namespace voxlink::fuzz {

using Input = std::span<const uint8_t>;

Status fuzzVxl(Input input);               // .vxl reader + validator (format/)
Status fuzzNrrd(Input input);              // NRRD, attached or detached, file lists
Status fuzzMetaImage(Input input);         // .mhd / .mha
Status fuzzNifti(Input input);             // .nii, .nii.gz
Status fuzzVvd(Input input);               // Voreen .vvd + raw file
Status fuzzVti(Input input);               // VTK XML image data
Status fuzzNpy(Input input);               // NumPy .npy
Status fuzzGslib(Input input);             // GSLIB / GEO-EAS grids, plain or zipped
Status fuzzRaw(Input input);               // headerless raw with --dims/--type from the input
Status fuzzDicom(Input input);             // DICOM series (GDCM behind its child-process guard)
Status fuzzImageStack(Input input);        // 2-D slice images / multi-page TIFF (OpenImageIO)
Status fuzzTransferFunction(Input input);  // TF JSON
Status fuzzParaViewPreset(Input input);    // ParaView colour-map JSON (viewer core)
Status fuzzKrigingPoints(Input input);     // kriging sample tables (CSV, GEO-EAS points)
Status fuzzScene(Input input);             // scene JSON (scene/)
Status fuzzMesh(Input input);              // OBJ (+ MTL), PLY, STL through assimp (geometry/)
Status fuzzParticles(Input input);         // PDB and `x y z r [material]` text (geometry/)

struct FuzzTarget {
  std::string_view name;  // fuzz executable fuzz_<name>, regression folder name
  Status (*run)(Input);
};

// Every target, in the order scripts/fuzz.sh runs them.
std::span<const FuzzTarget> fuzzTargets();
const FuzzTarget* findFuzzTarget(std::string_view name);

}  // namespace voxlink::fuzz
