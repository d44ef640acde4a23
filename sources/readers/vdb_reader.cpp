// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/vdb_reader.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cstring>

#include "sources/readers/detail/axes.h"
#include "sources/readers/detail/child_probe.h"
#include "sources/readers/reader_common.h"

namespace voxlink::sources {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;
using openvdb::FloatGrid;

class VdbSource final : public VolumeSource {
 public:
  VdbSource(VolumeInfo info, FloatGrid::ConstPtr grid, CoordBBox box)
      : grid_(std::move(grid)), box_(box), background_(grid_->background()) {
    info_ = std::move(info);
  }

  bool randomAccess() const override { return true; }
  bool hasInactiveVoxels() const override { return true; }

  // Inactive voxels read as the background even where a leaf stores another value there
  // (tools::copyToDense would copy those stored values), so each 8^3 block is resolved here:
  // a leaf gives per-voxel values and states, a tile one value and state for the whole block.
  Status read(uint32_t z0, uint32_t count, void* dst) override {
    return readChecked(z0, count, static_cast<float*>(dst), nullptr);
  }
  Status readActive(uint32_t z0, uint32_t count, uint8_t* dst) override {
    return readChecked(z0, count, nullptr, dst);
  }
  Status readWithActive(uint32_t z0, uint32_t count, void* dst, uint8_t* active) override {
    return readChecked(z0, count, static_cast<float*>(dst), active);
  }

 private:
  Status readChecked(uint32_t z0, uint32_t count, float* values, uint8_t* active) const {
    VOXLINK_RETURN_IF_ERROR(checkSliceRange(z0, count));
    try {
      readBlocks(z0, count, values, active);
    } catch (const std::exception& e) {
      return makeError(ErrorCode::kCorrupt, info_.path, ": OpenVDB failed reading slices ", z0,
                       "..", z0 + count - 1, " (", e.what(), ")");
    }
    return Status::ok();
  }

  // Values (background where inactive) into `values`, active flags into `active`; either may
  // be null.
  void readBlocks(uint32_t z0, uint32_t count, float* values, uint8_t* active) const {
    using Leaf = FloatGrid::TreeType::LeafNodeType;
    constexpr int kDim = static_cast<int>(Leaf::DIM);
    const Coord lo(box_.min().x(), box_.min().y(), box_.min().z() + static_cast<int>(z0));
    const Coord hi(box_.max().x(), box_.max().y(), lo.z() + static_cast<int>(count) - 1);
    const int64_t nx = info_.dims[0], ny = info_.dims[1];
    auto accessor = grid_->getConstAccessor();
    const auto blockStart = [](int v) { return v & ~(kDim - 1); };
    for (int bz = blockStart(lo.z()); bz <= hi.z(); bz += kDim) {
      for (int by = blockStart(lo.y()); by <= hi.y(); by += kDim) {
        for (int bx = blockStart(lo.x()); bx <= hi.x(); bx += kDim) {
          const Coord origin(bx, by, bz);
          const Coord a = Coord::maxComponent(origin, lo);
          const Coord b = Coord::minComponent(origin.offsetBy(kDim - 1), hi);
          const Leaf* leaf = accessor.probeConstLeaf(origin);
          float tileValue = background_;
          bool tileActive = false;
          if (!leaf) {
            float v;
            tileActive = accessor.probeValue(origin, v);
            if (tileActive) tileValue = v;
          }
          for (int z = a.z(); z <= b.z(); ++z) {
            for (int y = a.y(); y <= b.y(); ++y) {
              const int64_t rowStart = (int64_t{z - lo.z()} * ny + (y - lo.y())) * nx - lo.x();
              for (int x = a.x(); x <= b.x(); ++x) {
                bool on = tileActive;
                float v = tileValue;
                if (leaf) {
                  const auto offset = Leaf::coordToOffset(Coord(x, y, z));
                  on = leaf->isValueOn(offset);
                  v = on ? leaf->getValue(offset) : background_;
                }
                if (values) values[rowStart + x] = v;
                if (active) active[rowStart + x] = on ? 1 : 0;
              }
            }
          }
        }
      }
    }
  }

  FloatGrid::ConstPtr grid_;
  CoordBBox box_;
  float background_;
};

}  // namespace

Result<std::unique_ptr<VolumeSource>> openVdbDirect(const std::string& path,
                                                    const OpenOptions& options) {
  openvdb::initialize();
  // OpenVDB trusts a file's structure: some damaged files corrupt its heap or crash it instead
  // of throwing. Read every grid once in a child process first (this reads the file twice).
  const ProbeOutcome probe = probeInChild([&](const MarkFn&) {
    openvdb::io::File file(path);
    file.open(/*delayLoad=*/false);
    const openvdb::GridPtrVecPtr grids = file.readAllGridMetadata();  // kept alive for the loop
    for (const auto& meta : *grids) file.readGrid(meta->getName())->evalActiveVoxelBoundingBox();
  });
  if (probe.died)
    return makeError(ErrorCode::kCorrupt, path, ": OpenVDB crashed reading this file (",
                     describeDeath(probe), "); the file is damaged");
  if (probe.thrown)  // the same read here would throw the same, maybe slowly
    return makeError(ErrorCode::kCorrupt, path, ": OpenVDB cannot read it (", *probe.thrown, ")");
  openvdb::GridBase::Ptr base;
  std::string names;
  try {
    openvdb::io::File file(path);
    // No delayed loading: every leaf is read (and a damaged one throws) here, inside this try,
    // not later from a converter thread.
    file.open(/*delayLoad=*/false);
    openvdb::GridPtrVecPtr grids = file.readAllGridMetadata();
    std::string chosen = options.vdbGrid;
    for (const auto& g : *grids) {
      names += cat(names.empty() ? "" : ", ", "'", g->getName(), "' (", g->valueType(), ")");
      if (chosen.empty() && g->isType<FloatGrid>()) chosen = g->getName();
    }
    if (chosen.empty())
      return makeError(ErrorCode::kUnsupported, path, ": no float grid among ",
                       names.empty() ? "no grids" : names);
    if (!file.hasGrid(chosen))
      return makeError(ErrorCode::kInvalidArgument, path, ": --vdb-grid '", chosen,
                       "' not in the file; it holds ", names);
    base = file.readGrid(chosen);
    file.close();
  } catch (const openvdb::Exception& e) {
    return makeError(ErrorCode::kCorrupt, path, ": OpenVDB cannot read it (", e.what(), ")");
  } catch (const std::exception& e) {
    return makeError(ErrorCode::kIo, path, ": OpenVDB cannot read it (", e.what(), ")");
  }
  FloatGrid::Ptr grid = openvdb::gridPtrCast<FloatGrid>(base);
  if (!grid)
    return makeError(ErrorCode::kUnsupported, path, ": grid '", base->getName(), "' holds ",
                     base->valueType(), " values; only float grids are supported");

  const CoordBBox box = grid->evalActiveVoxelBoundingBox();
  if (box.empty())
    return makeError(ErrorCode::kUnsupported, path, ": grid '", grid->getName(),
                     "' has no active voxels");
  const openvdb::math::Transform& xform = grid->transform();
  if (!xform.isLinear())
    return makeError(ErrorCode::kUnsupported, path, ": grid '", grid->getName(), "': transform ",
                     xform.mapType(), " is not linear");
  const openvdb::Coord extent = box.dim();
  VOXLINK_RETURN_IF_ERROR(
      checkDims({uint64_t(extent.x()), uint64_t(extent.y()), uint64_t(extent.z())}, path,
                "active voxel bounding box"));

  VolumeInfo info;
  info.path = path;
  info.format = "vdb";
  info.type = ScalarType::kF32;
  info.dims = {uint32_t(extent.x()), uint32_t(extent.y()), uint32_t(extent.z())};
  const openvdb::Vec3d o = xform.indexToWorld(box.min());
  info.origin = {o.x(), o.y(), o.z()};
  std::array<Vec3, 3> axes{};
  for (int a = 0; a < 3; ++a) {
    openvdb::Coord step = box.min();
    step[a] += 1;
    const openvdb::Vec3d d = xform.indexToWorld(step) - o;
    axes[a] = {d.x(), d.y(), d.z()};
  }
  const AxesSummary s = summarizeAxes(axes, "grid transform axes");
  info.spacing = s.lengths;
  if (!s.note.empty()) info.notes.push_back(s.note);
  info.notes.push_back(
      cat("grid '", grid->getName(), "': dense over the active voxel bounding box ", "from index (",
          box.min().x(), ",", box.min().y(), ",", box.min().z(), ") to (", box.max().x(), ",",
          box.max().y(), ",", box.max().z(), "); inactive voxels read as the background ",
          grid->background(), " and are never kept"));
  VOXLINK_RETURN_IF_ERROR(checkSpacing(info.spacing, path, "grid transform"));
  VOXLINK_RETURN_IF_ERROR(applyOpenOptions(info, options));
  return std::unique_ptr<VolumeSource>(new VdbSource(std::move(info), grid, box));
}

}  // namespace voxlink::sources
