// SPDX-License-Identifier: BSD-3-Clause
#include "convert/vdb_export.h"

#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "base/output_file.h"
#include "format/gradient_codec.h"
#include "format/voxel_locator.h"

namespace voxlink::convert {

Result<VdbExportSummary> exportVdbDirect(const format::VoxLinkFile& file, const std::string& path,
                                         const base::ProgressCallback& progress) {
  if (file.isScene())
    return makeError(
        ErrorCode::kUnsupported, file.path(),
        ": OpenVDB export reads volume files (version 1); this is a scene (version 2)");
  openvdb::initialize();
  const format::FileHeader& h = file.header();
  // Index (i, j, k) -> world origin + spacing * (i, j, k), row-vector convention.
  openvdb::math::Mat4d toWorld = openvdb::math::Mat4d::identity();
  for (int a = 0; a < 3; ++a) {
    toWorld(a, a) = h.spacing[a];
    toWorld(3, a) = h.origin[a];
  }
  auto transform = openvdb::math::Transform::createLinearTransform(toWorld);
  auto values = openvdb::FloatGrid::create(0.0f);
  auto gradients = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
  values->setName("values");
  values->setGridClass(openvdb::GRID_FOG_VOLUME);
  gradients->setName("gradient");
  gradients->setVectorType(openvdb::VEC_COVARIANT_NORMALIZE);
  {
    auto v = values->getAccessor();
    auto g = gradients->getAccessor();
    const std::span<const uint16_t> codes = file.gradientCodes();
    // Setting the voxels is 80 % of the bar, writing the file the rest.
    const uint64_t voxels = std::max<uint64_t>(1, file.voxelCount());
    const uint64_t reportEvery = std::max<uint64_t>(1, voxels / 32);
    uint64_t nextReport = 0;
    format::VoxelLocator(file).forEachVoxel([&](uint32_t x, uint32_t y, uint32_t z, uint64_t i) {
      if (i >= nextReport) {
        base::reportProgress(progress, 0.8 * double(i) / double(voxels), "grids");
        nextReport = i + reportEvery;
      }
      const openvdb::Coord ijk{int(x), int(y), int(z)};
      v.setValue(ijk, static_cast<float>(file.value(i)));
      const std::array<float, 3> d = format::decodeGradient(codes[i]);
      g.setValue(ijk, openvdb::Vec3s(d[0], d[1], d[2]));
    });
  }
  for (openvdb::GridBase::Ptr grid :
       {openvdb::GridBase::Ptr(values), openvdb::GridBase::Ptr(gradients)}) {
    grid->setTransform(transform->copy());
    grid->insertMeta("voxlink_source_file", openvdb::StringMetadata(file.path()));
    grid->insertMeta("voxlink_meta", openvdb::StringMetadata(file.metaJson()));
    grid->insertMeta("voxlink_value_max_abs_error", openvdb::DoubleMetadata(h.valueMaxAbsError));
    grid->insertMeta("voxlink_gradient_codec", openvdb::StringMetadata("polar16, decoded"));
  }

  base::reportProgress(progress, 0.8, "writing");
  VOXLINK_ASSIGN_OR_RETURN(base::TempFile temp, base::createTempBeside(path, ".vdb"));
  ::close(temp.fd);
  // Through a stream of our own: openvdb::io::File does not check its stream, so a full disk
  // gave a cut-off file and success. The bytes are the same but for the archive's random UUID.
  try {
    std::ofstream out(temp.path, std::ios::binary | std::ios::trunc);
    openvdb::io::Stream(out).write({values, gradients});
    out.close();
    if (out.fail()) {
      const int e = errno;
      base::discardTemp(temp.path);
      return makeError(ErrorCode::kIo, path,
                       ": write failed: ", e ? std::strerror(e) : "I/O error");
    }
  } catch (const std::exception& e) {
    base::discardTemp(temp.path);
    return makeError(ErrorCode::kIo, path, ": OpenVDB could not write: ", e.what());
  }
  VOXLINK_RETURN_IF_ERROR(base::commitTemp(temp.path, path));
  base::reportProgress(progress, 1.0, "exported");
  VdbExportSummary summary;
  summary.voxels = values->activeVoxelCount();
  std::error_code ec;
  summary.bytes = std::filesystem::file_size(path, ec);
  return summary;
}

}  // namespace voxlink::convert
