// SPDX-License-Identifier: BSD-3-Clause
// NIfTI-1/NIfTI-2 volumes (.nii, .nii.gz). libnifti2 parses the header (both versions, byte
// order, the .hdr/.img pair names); the voxels are then streamed by our own raw/gzip data
// pieces, so a .nii.gz is decoded once, slice by slice, instead of being loaded whole.
#pragma once

#include <memory>
#include <string>

#include "sources/volume_source.h"

namespace voxlink::sources {

Result<std::unique_ptr<VolumeSource>> openNifti(const std::string& path,
                                                const OpenOptions& options);

}  // namespace voxlink::sources
