// SPDX-License-Identifier: BSD-3-Clause
#include "format/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "format/fragment_extent.h"
#include "format/gradient_codec.h"

namespace voxlink::format {
namespace {

double storedToSource(const VolumeDescription& d, uint32_t bits) {
  return storedBitsValue(d.valueType, bits) * d.valueScale + d.valueOffset;
}

}  // namespace

SceneBuilder::SceneBuilder(VolumeDescription description) : description_(std::move(description)) {}

void SceneBuilder::addVolumeSample(uint32_t x, uint32_t y, uint32_t z, uint32_t storedBits,
                                   uint16_t gradient) {
  entries_.push_back(Entry{x, y, z, kVolume, gradient, storedBits});
}

void SceneBuilder::addSurface(uint32_t x, uint32_t y, uint32_t z, uint16_t normalCode,
                              uint16_t material) {
  entries_.push_back(Entry{x, y, z, kSurfaceFragment, 0, surfaceWord(normalCode, material)});
}

void SceneBuilder::addSphereRef(uint32_t x, uint32_t y, uint32_t z, uint32_t sphere) {
  entries_.push_back(Entry{x, y, z, kSphere, 0, sphere});
}

void SceneBuilder::addFragments(uint32_t x, uint32_t y, uint32_t z,
                                std::span<const FragmentRecord> list) {
  entries_.push_back(Entry{x, y, z, kFragmentList, uint16_t(std::min<size_t>(list.size(), 0xFFFF)),
                           uint32_t(planes_.size())});
  planes_.insert(planes_.end(), list.begin(), list.end());
}

void SceneBuilder::addTriangleRefs(uint32_t x, uint32_t y, uint32_t z,
                                   std::span<const uint32_t> list) {
  entries_.push_back(Entry{x, y, z, kFragmentList, uint16_t(std::min<size_t>(list.size(), 0xFFFF)),
                           uint32_t(triangleRefs_.size())});
  triangleRefs_.insert(triangleRefs_.end(), list.begin(), list.end());
}

Status SceneBuilder::appendList(const Entry& e, uint32_t count, SceneSections& scene) const {
  if (count == 0 || count > kMaxFragmentsPerVoxel)
    return makeError(ErrorCode::kTooLarge, "voxel (", e.x, ", ", e.y, ", ", e.z, "): ", count,
                     count == 0xFFFF ? " or more" : "", " fragments; the format holds 1 to ",
                     kMaxFragmentsPerVoxel, " per voxel");
  if (surfaceMode_ == SurfaceMode::kPlanes) {
    if (size_t(e.payload) + count > planes_.size())
      return makeError(ErrorCode::kInvalidArgument, "voxel (", e.x, ", ", e.y, ", ", e.z,
                       "): fragment list out of range");
    for (uint32_t i = 0; i < count; ++i) {
      const FragmentRecord& f = planes_[e.payload + i];
      if (surfaceMaterial(f.word) >= materials_.size())
        return makeError(ErrorCode::kInvalidArgument, "voxel (", e.x, ", ", e.y, ", ", e.z,
                         "): fragment material ", surfaceMaterial(f.word),
                         " is not in the table of ", materials_.size());
      if (!isValidExtent(f.extent))
        return makeError(ErrorCode::kInvalidArgument, "voxel (", e.x, ", ", e.y, ", ", e.z,
                         "): fragment extent 0x", std::hex, f.extent, " is not a box");
      scene.fragments.push_back(f);
    }
    return Status::ok();
  }
  if (size_t(e.payload) + count > triangleRefs_.size())
    return makeError(ErrorCode::kInvalidArgument, "voxel (", e.x, ", ", e.y, ", ", e.z,
                     "): triangle list out of range");
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t t = triangleRefs_[e.payload + i];
    if (t >= triangles_.size() || (i > 0 && t <= triangleRefs_[e.payload + i - 1]))
      return makeError(ErrorCode::kInvalidArgument, "voxel (", e.x, ", ", e.y, ", ", e.z,
                       "): triangle ", t, " is not ascending or not in the table of ",
                       triangles_.size());
    scene.triangleRefs.push_back(t);
  }
  return Status::ok();
}

Result<BrickedVolume> SceneBuilder::build(std::string metaJson) const {
  VOXLINK_RETURN_IF_ERROR(checkDescription(description_));
  const VolumeDescription& d = description_;
  if (materials_.size() > kMaxMaterials)
    return makeError(ErrorCode::kTooLarge, materials_.size(),
                     " materials exceed the format's limit of ", kMaxMaterials);
  struct Keyed {
    uint64_t key;
    const Entry* entry;
  };
  std::vector<Keyed> keyed;
  keyed.reserve(entries_.size());
  bool geometry = false;
  for (const Entry& e : entries_) {
    if (e.x >= d.dims[0] || e.y >= d.dims[1] || e.z >= d.dims[2])
      return makeError(ErrorCode::kInvalidArgument, "voxel (", e.x, ", ", e.y, ", ", e.z,
                       ") lies outside the ", d.dims[0], "x", d.dims[1], "x", d.dims[2], " volume");
    if (e.kind == kSurfaceFragment && surfaceMaterial(e.payload) >= materials_.size())
      return makeError(ErrorCode::kInvalidArgument, "voxel (", e.x, ", ", e.y, ", ", e.z,
                       "): material ", surfaceMaterial(e.payload), " is not in the table of ",
                       materials_.size());
    if (e.kind == kSphere && e.payload >= spheres_.size())
      return makeError(ErrorCode::kInvalidArgument, "voxel (", e.x, ", ", e.y, ", ", e.z,
                       "): sphere ", e.payload, " is not in the table of ", spheres_.size());
    geometry = geometry || e.kind != kVolume;
    keyed.push_back({fileOrderKey(d, e.x, e.y, e.z), &e});
  }
  // Volume first, then the surface, then spheres by index: the order each voxel's data is read.
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) {
    if (a.key != b.key) return a.key < b.key;
    if (a.entry->kind != b.entry->kind) return a.entry->kind < b.entry->kind;
    return a.entry->payload < b.entry->payload;
  });

  BrickedVolumeBuilder bricks(d);
  SceneSections scene;
  scene.materials = materials_;
  scene.spheres = spheres_;
  scene.surfaceMode = surfaceMode_;
  scene.triangles = triangles_;
  const bool lists = surfaceMode_ != SurfaceMode::kMean;
  double lo = INFINITY, hi = -INFINITY;
  uint64_t voxel = 0;
  for (size_t i = 0; i < keyed.size();) {
    const Entry& first = *keyed[i].entry;
    uint32_t bits = 0;
    uint16_t gradient = kZeroGradient;
    uint32_t surface = kNoSurface;
    bool volume = false;
    const Entry* list = nullptr;
    const size_t refsBefore = scene.sphereRefs.size();
    size_t j = i;
    for (; j < keyed.size() && keyed[j].key == keyed[i].key; ++j) {
      const Entry& e = *keyed[j].entry;
      const bool repeated = j > i && keyed[j - 1].entry->kind == e.kind;
      if (e.kind == kVolume) {
        if (repeated)
          return makeError(ErrorCode::kInvalidArgument, "voxel (", e.x, ", ", e.y, ", ", e.z,
                           ") given two volume samples");
        volume = true;
        bits = e.payload;
        gradient = e.gradient;
        const double v = storedToSource(d, bits);
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      } else if (e.kind == kSurfaceFragment) {
        if (repeated)
          return makeError(ErrorCode::kInvalidArgument, "voxel (", e.x, ", ", e.y, ", ", e.z,
                           ") given two surface fragments");
        surface = e.payload;
      } else if (e.kind == kFragmentList) {
        if (repeated || !lists)
          return makeError(ErrorCode::kInvalidArgument, "voxel (", e.x, ", ", e.y, ", ", e.z,
                           lists ? ") given two fragment lists"
                                 : ") given a fragment list in a file without them");
        list = &e;
      } else if (!(repeated && keyed[j - 1].entry->payload == e.payload)) {
        scene.sphereRefs.push_back(e.payload);  // a sphere named twice counts once
      }
    }
    bricks.add(first.x, first.y, first.z, bits, gradient);
    if (voxel % 32 == 0) {
      scene.volumeMask.push_back(0);
      scene.surfaceMask.push_back(0);
      if (!spheres_.empty()) scene.sphereMask.push_back(0);
    }
    const uint32_t bit = 1u << (voxel % 32);
    if (volume) scene.volumeMask.back() |= bit;
    if (surface != kNoSurface) {
      scene.surfaceMask.back() |= bit;
      scene.surface.push_back(surface);
    }
    if (lists) {
      if ((surface != kNoSurface) != (list != nullptr))
        return makeError(ErrorCode::kInvalidArgument, "voxel (", first.x, ", ", first.y, ", ",
                         first.z,
                         list ? ") has a fragment list but no surface fragment"
                              : ") has a surface fragment but no fragment list");
      if (list) {
        scene.fragmentStart.push_back(static_cast<uint32_t>(surfaceMode_ == SurfaceMode::kPlanes
                                                                ? scene.fragments.size()
                                                                : scene.triangleRefs.size()));
        VOXLINK_RETURN_IF_ERROR(appendList(*list, list->gradient, scene));
      }
    }
    if (scene.sphereRefs.size() > refsBefore) {
      scene.sphereMask.back() |= bit;
      scene.sphereRefStart.push_back(static_cast<uint32_t>(refsBefore));
    }
    ++voxel;
    i = j;
  }
  if (!spheres_.empty())
    scene.sphereRefStart.push_back(static_cast<uint32_t>(scene.sphereRefs.size()));
  if (lists) {
    const size_t total =
        surfaceMode_ == SurfaceMode::kPlanes ? scene.fragments.size() : scene.triangleRefs.size();
    if (total > kMaxVoxels)
      return makeError(ErrorCode::kTooLarge, total, " fragments exceed the format's limit of ",
                       kMaxVoxels);
    scene.fragmentStart.push_back(static_cast<uint32_t>(total));
  }

  VOXLINK_ASSIGN_OR_RETURN(BrickedVolume built, bricks.build(std::move(metaJson)));
  built.description.valueMin = std::isfinite(lo) ? lo : 0.0;
  built.description.valueMax = std::isfinite(hi) ? hi : 0.0;
  if (!geometry) return built;
  // VALU and GRAD keep the volume voxels only, in voxel order (their VMSK slots).
  const size_t valueSize = storedSize(d.valueType);
  size_t slot = 0;
  for (uint64_t v = 0; v < voxel; ++v) {
    if (!((scene.volumeMask[v / 32] >> (v % 32)) & 1u)) continue;
    std::memmove(built.values.data() + slot * valueSize, built.values.data() + v * valueSize,
                 valueSize);
    built.gradients[slot] = built.gradients[v];
    ++slot;
  }
  built.values.resize(slot * valueSize);
  built.gradients.resize(slot);
  built.scene = std::move(scene);
  return built;
}

}  // namespace voxlink::format
