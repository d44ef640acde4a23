// SPDX-License-Identifier: BSD-3-Clause
#include "tests/viewer/volume_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "convert/converter.h"
#include "format/gradient_codec.h"
#include "format/half.h"
#include "pack/open_file.h"
#include "tests/support/test_util.h"

namespace voxlink::render::testing {

using render::gl::RenderTarget;
using render::gl::VolumeRenderer;

Result<format::BrickedVolume> sparsify(const DenseVolume& v,
                                       const std::function<bool(double)>& keep,
                                       const SparseOptions& o) {
  format::VolumeDescription d;
  d.dims = v.dims;
  d.brickSize = o.brickSize;
  d.predominantAxis = o.axis;
  d.valueType = o.type;
  d.sourceType = v.sourceType;
  d.spacing = v.spacing;
  d.origin = v.origin;
  d.valueScale = o.scale;
  d.valueOffset = o.offset;
  format::BrickedVolumeBuilder builder(d);
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (uint32_t z = 0; z < v.dims[2]; ++z)
    for (uint32_t y = 0; y < v.dims[1]; ++y)
      for (uint32_t x = 0; x < v.dims[0]; ++x) {
        const double value = v.at(x, y, z);
        if (!keep(value)) continue;
        lo = std::min(lo, value);
        hi = std::max(hi, value);
        const double stored = (value - o.offset) / o.scale;
        uint32_t bits = 0;
        switch (o.type) {
          case StoredType::kU8:
          case StoredType::kU16:
            bits = uint32_t(std::lround(stored));
            break;
          case StoredType::kF16:
            bits = format::floatToHalf(float(stored));
            break;
          case StoredType::kF32: {
            const float f = float(stored);
            std::memcpy(&bits, &f, 4);
          }
        }
        const glm::dvec3 g = v.gradient(x, y, z);
        builder.add(x, y, z, bits, format::encodeGradient(g.x, g.y, g.z));
      }
  VOXLINK_ASSIGN_OR_RETURN(format::BrickedVolume sparse, builder.build());
  sparse.description.valueMin = builder.size() ? lo : 0.0;
  sparse.description.valueMax = builder.size() ? hi : 0.0;
  return sparse;
}

Result<format::VoxLinkFile> writeAndOpen(const format::BrickedVolume& sparse,
                                         const std::string& path) {
  VOXLINK_RETURN_IF_ERROR(format::writeBrickedVolume(path, sparse));
  return pack::openFile(path);
}

Result<format::VoxLinkFile> thresholdedFile(const DenseVolume& volume, double threshold, uint32_t n,
                                            format::Axis axis, const std::string& path) {
  SparseOptions o;
  o.brickSize = n;
  o.axis = axis;
  VOXLINK_ASSIGN_OR_RETURN(format::BrickedVolume sparse,
                           sparsify(
                               volume, [threshold](double v) { return v > threshold; }, o));
  return writeAndOpen(sparse, path);
}

DenseVolume makeVolume(std::array<uint32_t, 3> dims, std::array<double, 3> spacing,
                       const std::function<double(int, int, int)>& f) {
  DenseVolume v;
  v.dims = dims;
  v.spacing = spacing;
  v.sourceType = ScalarType::kU8;
  v.values.resize(v.voxelCount());
  for (uint32_t z = 0; z < dims[2]; ++z)
    for (uint32_t y = 0; y < dims[1]; ++y)
      for (uint32_t x = 0; x < dims[0]; ++x) v.values[v.index(x, y, z)] = f(int(x), int(y), int(z));
  return v;
}

tf::TransferFunction rampTf(double threshold, double width, double alpha, double lo, double hi) {
  tf::TransferFunction tf;
  tf.opacity = {{threshold, 0.0}, {threshold + width, alpha}};
  tf.color = {{lo, {0.9, 0.35, 0.2}}, {0.5 * (lo + hi), {0.95, 0.85, 0.6}}, {hi, {1.0, 1.0, 1.0}}};
  return tf;
}

std::string toothPath() { return voxlink::testing::dataPath("ct/tooth_103x94x161_uint8.raw"); }

sources::OpenOptions toothOpenOptions() {
  sources::OpenOptions options;
  options.dims = std::array<uint32_t, 3>{103, 94, 161};
  options.type = ScalarType::kU8;
  options.format = "raw";
  return options;
}

Result<DenseVolume> loadTooth() { return loadDenseVolume(toothPath(), toothOpenOptions()); }

Result<format::VoxLinkFile> convertWithThreshold(const std::string& source,
                                                 const sources::OpenOptions& open,
                                                 const std::string& threshold,
                                                 const std::string& output, uint32_t brickSize,
                                                 format::Axis axis) {
  VOXLINK_ASSIGN_OR_RETURN(auto volume, sources::openVolume(source, open));
  convert::ConvertOptions options;
  options.brickSize = brickSize;
  options.axis = axis;
  options.threads = 2;
  options.sourceOptions = open;
  VOXLINK_ASSIGN_OR_RETURN(options.classification, convert::thresholdClassification({threshold}));
  VOXLINK_RETURN_IF_ERROR(convert::convertVolume(*volume, options, output).status());
  return pack::openFile(output);
}

RenderPair renderBoth(VolumeRenderer& renderer, const ReferenceRenderer& reference,
                      const Camera& camera, const RenderSettings& settings) {
  RenderPair pair;
  RenderTarget target;
  const Status s = renderer.render(camera, settings, target);
  EXPECT_TRUE(s.isOk()) << (s ? "" : s.message());
  pair.gl = target.read();
  pair.reference = reference.render(camera, settings);
  auto e = compareImages(pair.gl, pair.reference);
  EXPECT_TRUE(e.isOk());
  if (e) pair.error = *e;
  return pair;
}

}  // namespace voxlink::render::testing
