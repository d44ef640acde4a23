// SPDX-License-Identifier: BSD-3-Clause
#include "scene/detail/scene_ranks.h"

#include <algorithm>
#include <cstring>
#include <type_traits>

#include "base/crc32c.h"

namespace voxlink::scene {
namespace {

template <typename T>
std::span<const uint8_t> asBytes(const std::vector<T>& v) {
  return {reinterpret_cast<const uint8_t*>(v.data()), v.size() * sizeof(T)};
}

// Appends every rank's part (bytes of T) to `out`, in rank order.
template <typename T>
void gatherInto(base::RankGroup& ranks, std::vector<T>& out) {
  static_assert(std::is_trivially_copyable_v<T>);
  auto parts = base::gatherLargeToRoot(ranks, asBytes(out));
  out.clear();
  for (const std::vector<uint8_t>& part : parts) {
    const size_t at = out.size();
    out.resize(at + part.size() / sizeof(T));
    std::memcpy(out.data() + at, part.data(), part.size() / sizeof(T) * sizeof(T));
  }
}

struct GeometryPrint {
  uint64_t triangles, spheres, materials, checksum;
};

GeometryPrint printOf(const PlacedScene& p) {
  uint32_t crc = base::crc32c(p.mesh.positions.data(), p.mesh.positions.size() * sizeof(float));
  crc = base::crc32c(p.mesh.triangles.data(), p.mesh.triangles.size() * sizeof(uint32_t), crc);
  crc = base::crc32c(p.mesh.triangleMaterials.data(),
                     p.mesh.triangleMaterials.size() * sizeof(uint16_t), crc);
  for (const geometry::Sphere& s : p.spheres) {  // field by field: Sphere has padding
    crc = base::crc32c(s.center.data(), sizeof s.center, crc);
    crc = base::crc32c(&s.radius, sizeof s.radius, crc);
    crc = base::crc32c(&s.material, sizeof s.material, crc);
  }
  crc = base::crc32c(p.materials.data(), p.materials.size() * sizeof(format::MaterialRecord), crc);
  return {p.mesh.triangleCount(), p.spheres.size(), p.materials.size(), crc};
}

}  // namespace

geometry::ZSlab rankSlab(uint32_t depth, uint32_t brick, int rank, int ranks) {
  const uint64_t layers = (uint64_t(depth) + brick - 1) / brick;
  const uint64_t first = layers * uint64_t(rank) / uint64_t(ranks);
  const uint64_t end = layers * uint64_t(rank + 1) / uint64_t(ranks);
  return {uint32_t(std::min<uint64_t>(depth, first * brick)),
          uint32_t(std::min<uint64_t>(depth, end * brick))};
}

SlabVoxels gatherSlabVoxels(base::RankGroup& ranks, SlabVoxels mine) {
  if (ranks.size() == 1) return mine;
  gatherInto(ranks, mine.surface);
  gatherInto(ranks, mine.sphereRefs);
  gatherInto(ranks, mine.listLength);
  gatherInto(ranks, mine.planes);
  gatherInto(ranks, mine.triangleRefs);
  std::vector<uint64_t> tally = mine.normalError.words();
  tally.push_back(mine.sphereVoxels);
  uint64_t offsetErrorBits = 0;
  std::memcpy(&offsetErrorBits, &mine.maxOffsetError, sizeof offsetErrorBits);
  tally.push_back(offsetErrorBits);
  tally.push_back(mine.planePairsLeftOut);
  const auto parts = ranks.gatherToRoot(asBytes(tally));
  SlabVoxels all;
  all.surface = std::move(mine.surface);
  all.sphereRefs = std::move(mine.sphereRefs);
  all.listLength = std::move(mine.listLength);
  all.planes = std::move(mine.planes);
  all.triangleRefs = std::move(mine.triangleRefs);
  for (const std::vector<uint8_t>& part : parts) {
    std::vector<uint64_t> words(part.size() / sizeof(uint64_t));
    std::memcpy(words.data(), part.data(), words.size() * sizeof(uint64_t));
    all.normalError.merge(geometry::NormalErrorTally::fromWords(words.data()));
    all.sphereVoxels += words[geometry::NormalErrorTally::kWords];
    double offsetError = 0;
    std::memcpy(&offsetError, &words[geometry::NormalErrorTally::kWords + 1], sizeof offsetError);
    all.maxOffsetError = std::max(all.maxOffsetError, offsetError);
    all.planePairsLeftOut += words[geometry::NormalErrorTally::kWords + 2];
  }
  return all;
}

Status checkSameGeometry(base::RankGroup& ranks, const PlacedScene& placed,
                         const std::string& scenePath) {
  if (ranks.size() == 1) return Status::ok();
  const GeometryPrint mine = printOf(placed);
  std::vector<GeometryPrint> all(static_cast<size_t>(ranks.size()));
  ranks.allGather(&mine, sizeof mine, all.data());
  const GeometryPrint& root = all[0];
  for (size_t r = 1; r < all.size(); ++r) {
    const GeometryPrint& p = all[r];
    if (std::memcmp(&p, &root, sizeof p) == 0) continue;
    return makeError(ErrorCode::kInvalidArgument, "rank ", r, ": ", scenePath,
                     ": its meshes and particle files differ from rank 0's (", p.triangles,
                     " triangles, ", p.spheres, " spheres, ", p.materials, " materials against ",
                     root.triangles, ", ", root.spheres, ", ", root.materials,
                     "; or the same counts with other coordinates)");
  }
  return Status::ok();
}

void broadcastDescription(base::RankGroup& ranks, format::VolumeDescription& description) {
  static_assert(std::is_trivially_copyable_v<format::VolumeDescription>);
  if (ranks.size() == 1) return;
  std::string bytes(sizeof description, '\0');
  std::memcpy(bytes.data(), &description, sizeof description);
  ranks.broadcast(bytes, 0);
  std::memcpy(&description, bytes.data(), sizeof description);
}

}  // namespace voxlink::scene
