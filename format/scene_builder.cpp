// SPDX-License-Identifier: BSD-3-Clause
#include "format/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <cstring>

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
  double lo = INFINITY, hi = -INFINITY;
  uint64_t voxel = 0;
  for (size_t i = 0; i < keyed.size();) {
    const Entry& first = *keyed[i].entry;
    uint32_t bits = 0;
    uint16_t gradient = kZeroGradient;
    uint32_t surface = kNoSurface;
    bool volume = false;
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
    if (scene.sphereRefs.size() > refsBefore) {
      scene.sphereMask.back() |= bit;
      scene.sphereRefStart.push_back(static_cast<uint32_t>(refsBefore));
    }
    ++voxel;
    i = j;
  }
  if (!spheres_.empty())
    scene.sphereRefStart.push_back(static_cast<uint32_t>(scene.sphereRefs.size()));

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
