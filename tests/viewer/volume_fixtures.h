// SPDX-License-Identifier: BSD-3-Clause
// Small volumes for viewer tests: dense volumes built from formulas, and VoxLink files made from
// them by keeping the voxels a predicate keeps, with gradients computed exactly as the
// reference renderer computes them (DenseVolume::gradient). This stands in for the converter
// where a test needs a file shaped in a particular way.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "format/bricked_volume.h"
#include "format/voxlink_file.h"
#include "render/dense_volume.h"
#include "render/gl/detail/volume_renderer.h"
#include "render/image.h"
#include "render/reference_renderer.h"
#include "tf/transfer_function.h"

namespace voxlink::render::testing {

using render::gl::VolumeRenderer;

struct SparseOptions {
  uint32_t brickSize = 8;
  format::Axis axis = format::Axis::kZ;
  StoredType type = StoredType::kU8;
  double scale = 1.0;  // source = stored * scale + offset
  double offset = 0.0;
};

// Keeps the voxels for which keep(value) holds.
Result<format::BrickedVolume> sparsify(const DenseVolume& volume,
                                       const std::function<bool(double)>& keep,
                                       const SparseOptions& options);
// Writes the sparse file to `path` and opens it.
Result<format::VoxLinkFile> writeAndOpen(const format::BrickedVolume& sparse,
                                         const std::string& path);
// Keeps the voxels above `threshold` with brick size n and predominant axis `axis`, writes the
// file to `path` and opens it.
Result<format::VoxLinkFile> thresholdedFile(const DenseVolume& volume, double threshold, uint32_t n,
                                            format::Axis axis, const std::string& path);

// A dense volume filled by f(x, y, z) (index coordinates).
DenseVolume makeVolume(std::array<uint32_t, 3> dims, std::array<double, 3> spacing,
                       const std::function<double(int, int, int)>& f);

// A TF that is transparent below `threshold` and ramps to `alpha` over `width` above it, with
// a colour ramp over [lo, hi].
tf::TransferFunction rampTf(double threshold, double width, double alpha, double lo, double hi);

// The tooth CT (103x94x161 u8) from the shared data, or an error when it is missing.
Result<DenseVolume> loadTooth();
sources::OpenOptions toothOpenOptions();
std::string toothPath();

// Runs the project's converter (convert::convertVolume) on a source, keeping values >= threshold.
Result<format::VoxLinkFile> convertWithThreshold(const std::string& source,
                                                 const sources::OpenOptions& open,
                                                 const std::string& threshold,
                                                 const std::string& output, uint32_t brickSize = 8,
                                                 format::Axis axis = format::Axis::kZ);

// Renders with the GL VoxLink renderer and with the reference; fails the test on GL errors.
struct RenderPair {
  Image gl, reference;
  ImageError error;
};
RenderPair renderBoth(VolumeRenderer& renderer, const ReferenceRenderer& reference,
                      const Camera& camera, const RenderSettings& settings);

}  // namespace voxlink::render::testing
