// SPDX-License-Identifier: BSD-3-Clause
#include "fuzz/fuzz_targets.h"

#include <array>

namespace voxlink::fuzz {
namespace {

constexpr std::array kTargets{
    FuzzTarget{"vxl", fuzzVxl},
    FuzzTarget{"nrrd", fuzzNrrd},
    FuzzTarget{"metaimage", fuzzMetaImage},
    FuzzTarget{"nifti", fuzzNifti},
    FuzzTarget{"vvd", fuzzVvd},
    FuzzTarget{"vti", fuzzVti},
    FuzzTarget{"npy", fuzzNpy},
    FuzzTarget{"gslib", fuzzGslib},
    FuzzTarget{"raw", fuzzRaw},
    FuzzTarget{"dicom", fuzzDicom},
    FuzzTarget{"image_stack", fuzzImageStack},
    FuzzTarget{"transfer_function", fuzzTransferFunction},
    FuzzTarget{"paraview_preset", fuzzParaViewPreset},
    FuzzTarget{"kriging_points", fuzzKrigingPoints},
    FuzzTarget{"scene", fuzzScene},
    FuzzTarget{"mesh", fuzzMesh},
    FuzzTarget{"particles", fuzzParticles},
};

}  // namespace

std::span<const FuzzTarget> fuzzTargets() { return kTargets; }

const FuzzTarget* findFuzzTarget(std::string_view name) {
  for (const FuzzTarget& t : kTargets)
    if (t.name == name) return &t;
  return nullptr;
}

}  // namespace voxlink::fuzz
