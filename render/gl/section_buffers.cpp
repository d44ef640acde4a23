// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/detail/section_buffers.h"

#include <algorithm>
#include <bit>
#include <cstdlib>

#include "base/process_memory.h"
#include "format/scene_index.h"
#include "render/brick_bounds.h"
#include "render/brick_lookup.h"
#include "render/gl/detail/row_words.h"
#include "render/gl/detail/voxel_words.h"

namespace voxlink::render::gl {

namespace {

// An array to upload: a section of the file, or a table derived from it.
struct GpuArray {
  std::string name;          // for errors
  const char* accessor;      // GLSL function returning element i
  const char* block;         // prefix of the block and array names
  uint32_t wordsPerElement;  // 1: uint, 2: uvec2, 4: uvec4
  std::span<const uint8_t> bytes;
};

std::span<const uint8_t> bytesOf(const std::vector<uint32_t>& words) {
  return {reinterpret_cast<const uint8_t*>(words.data()), words.size() * 4};
}

GpuArray section(const format::VoxLinkFile& file, format::SectionId id, const char* accessor,
                 const char* block) {
  return {cat("section ", format::sectionName(id)), accessor, block, 1, file.sectionBytes(id)};
}

// Per occupied brick: (box of its stored voxels, its first voxel).
std::vector<uint32_t> brickEntries(const format::VoxLinkFile& file,
                                   const std::vector<uint32_t>& boxes) {
  const auto firstVoxels = file.brickVoxelBase();
  std::vector<uint32_t> entries(2 * boxes.size());
  for (size_t k = 0; k < boxes.size(); ++k) {
    entries[2 * k] = boxes[k];
    entries[2 * k + 1] = firstVoxels[k];
  }
  return entries;
}

// Per occupied brick: the occupied index of the brick next to it along `axis`, or kEmptyBrick.
std::vector<uint32_t> nextAlongAxis(const BrickRange& range, const std::vector<uint32_t>& index,
                                    uint64_t bricks, uint32_t axis) {
  std::vector<uint32_t> out(bricks, kEmptyBrick);
  for (uint32_t z = 0; z < range.size[2]; ++z)
    for (uint32_t y = 0; y < range.size[1]; ++y)
      for (uint32_t x = 0; x < range.size[0]; ++x) {
        const uint32_t k = index[(uint64_t{z} * range.size[1] + y) * range.size[0] + x];
        uint32_t c[3] = {x, y, z};
        if (k == kEmptyBrick || ++c[axis] >= range.size[axis]) continue;
        out[k] = index[(uint64_t{c[2]} * range.size[1] + c[1]) * range.size[0] + c[0]];
      }
  return out;
}

std::string ivec3Of(const std::array<uint32_t, 3>& v) {
  return cat("ivec3(", v[0], ", ", v[1], ", ", v[2], ")");
}

// What the upload adds to the process, checked before anything is built: the derived tables
// (brick index and dual boxes over the occupied bricks' box, per occupied brick its box and
// entry) while they are built, and every uploaded array once more (llvmpipe keeps GL buffers in
// host memory; a GPU driver stages them).
Status checkUploadFits(const format::VoxLinkFile& file, const BrickRange& occupied) {
  const uint64_t occupiedBricks = file.occupiedBrickCount();
  const uint64_t tables =
      4 * occupied.count() + 20 * dualBrickRange(occupied).count() + 8 * occupiedBricks;
  uint64_t sections = 0;
  for (const format::SectionEntry& e : file.sectionTable())
    if (e.id != uint32_t(format::SectionId::kMeta)) sections += e.bytes;
  // The GRAD section goes up as voxel words: 4 bytes per voxel for its 2 (voxel_words.h); rows
  // as row words, 4 bytes per row (row_words.h).
  const uint64_t n = file.header().brickSize;
  // Row words' aprons copy up to one voxel word per row.
  const uint64_t needed = 2 * tables + 4 * occupiedBricks + 2 * sections + 4 * file.voxelCount() +
                          16 * occupiedBricks * n * n;
  const uint64_t available = base::memoryForThisProcess();
  if (needed > available)
    return makeError(ErrorCode::kTooLarge, file.path(), ": rendering needs ", needed,
                     " bytes (its sections and brick tables over the ", occupied.size[0], " x ",
                     occupied.size[1], " x ", occupied.size[2],
                     " bricks around the occupied ones), more than the ", available,
                     " bytes this process may use");
  return Status::ok();
}

// Row groups on GPUs, row words on CPU rasterizers (row_words.h); VOXLINK_ROW_GROUPS=0 or 1
// decides in place of the renderer's name (benchmarks of either layout on either).
bool useRowGroups(SectionBufferOptions::RowGroups choice) {
  using RowGroups = SectionBufferOptions::RowGroups;
  if (choice != RowGroups::kAuto) return choice == RowGroups::kOn;
  if (const char* env = std::getenv("VOXLINK_ROW_GROUPS"); env && *env) return env[0] != '0';
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string renderer = name ? name : "";
  for (const char* cpu : {"llvmpipe", "softpipe", "SwiftShader"})
    if (renderer.find(cpu) != std::string::npos) return false;
  return true;
}

}  // namespace

Result<SectionBuffers> SectionBuffers::upload(const format::VoxLinkFile& file,
                                              const SectionBufferOptions& options) {
  GLint maxTexels = 0, maxUnits = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  glGetIntegerv(GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS, &maxUnits);
  // Chunks hold a power-of-two number of 4-byte words, within what one buffer texture may address.
  uint64_t limit = uint64_t(std::max(maxTexels, 16)) * 4;
  if (options.maxChunkBytes != 0) limit = std::min(limit, options.maxChunkBytes);
  limit = std::bit_floor(std::max<uint64_t>(limit, 64));
  const uint64_t chunkWords = limit / 4;

  const BrickRange occupied = occupiedBrickRange(file);
  const BrickRange dual = dualBrickRange(occupied);
  VOXLINK_RETURN_IF_ERROR(checkUploadFits(file, occupied));
  const std::vector<uint32_t> brickIndex = occupiedIndexByBrick(file, occupied);
  const std::vector<uint32_t> boxes = brickBounds(file);
  const std::vector<uint32_t> dualBoxes = dualBrickBoxes(file, occupied, boxes);
  const std::vector<uint32_t> entries = brickEntries(file, boxes);
  // The 8 bricks' indices per dual brick, where 16 bits hold every occupied index.
  const bool dualIndices = dualBrickIndicesFit(file.occupiedBrickCount());
  const std::vector<uint32_t> dualBricks =
      dualIndices ? dualBrickIndices(occupied, brickIndex) : std::vector<uint32_t>();
  // 8-bit values ride in the voxel words; wider ones stay in VALU (VXL_VALUE_BYTES).
  const bool valuesInWords = storedSize(static_cast<StoredType>(file.header().valueType)) == 1;
  const auto values = file.sectionBytes(format::SectionId::kValues);
  std::vector<uint32_t> voxelWords =
      packVoxelWords(file.sectionBytes(format::SectionId::kGradients),
                     valuesInWords ? values : std::span<const uint8_t>());
  // Bricks up to 16^3: mask and start of a row in one word, in place of MASK and ROWS; with an
  // apron along w where the voxel indices may change (8-bit values, no scene sections), on GPUs
  // in groups of 4 rows.
  const uint32_t n = file.header().brickSize;
  const uint64_t bricks = file.occupiedBrickCount();
  const bool apron =
      valuesInWords && !file.isScene() && rowWordsApronFit(n, file.voxelCount(), bricks * n * n);
  const bool rowsGlobal = apron || rowWordsGlobal(n, file.voxelCount());
  std::vector<uint32_t> rowWords;
  if (apron) {
    ApronRows rows = packApronRows(
        n, bricks, file.rowMaskWords(), file.rowStarts(), file.brickVoxelBase(), voxelWords,
        nextAlongAxis(occupied, brickIndex, bricks, file.header().predominantAxis));
    rowWords = std::move(rows.rowWords);
    voxelWords = std::move(rows.voxelWords);
  } else if (rowWordsFit(n)) {
    rowWords = packRowWords(n, bricks, file.rowMaskWords(), file.rowStarts(),
                            rowsGlobal ? file.brickVoxelBase() : std::span<const uint32_t>());
  }
  const uint64_t voxelSlots = voxelWords.size();
  std::vector<GpuArray> arrays = {
      {"voxel words", "voxelWord", "VxlVoxelWord", 1, bytesOf(voxelWords)},
      {"brick index table", "brickIndexWord", "VxlBrickIndex", 1, bytesOf(brickIndex)},
      {"dual brick boxes", "dualBoxWord", "VxlDualBox", 1, bytesOf(dualBoxes)},
      {"brick entries", "brickEntry", "VxlBrickEntry", 2, bytesOf(entries)},
  };
  if (dualIndices)
    arrays.push_back(
        {"dual brick indices", "dualIndexWords", "VxlDualIndex", 4, bytesOf(dualBricks)});
  if (!valuesInWords)
    arrays.push_back(section(file, format::SectionId::kValues, "valuWord", "VxlValu"));
  const bool groups = apron && useRowGroups(options.rowGroups);
  if (groups) {
    rowWords = packRowGroups(n, rowWords);
    arrays.push_back({"row groups", "rowGroup", "VxlRowGroup", 2, bytesOf(rowWords)});
  } else if (rowWordsFit(n)) {
    arrays.push_back({"row words", "rowWord", "VxlRowWord", 1, bytesOf(rowWords)});
  } else {
    arrays.push_back(section(file, format::SectionId::kRowStart, "rowsWord", "VxlRows"));
    arrays.push_back(section(file, format::SectionId::kRowMask, "maskWord", "VxlMask"));
  }
  // Scenes (version 2): the geometry sections as they are, and per mask the set bits before
  // each word, derived here (shaders/voxlink_scene.glsl).
  const format::SceneIndex index(file);
  if (file.isScene()) {
    arrays.push_back(section(file, format::SectionId::kMaterials, "matlWord", "VxlMatl"));
    arrays.push_back(section(file, format::SectionId::kVolumeMask, "vmskWord", "VxlVmsk"));
    arrays.push_back(
        {"volume mask ranks", "vmskRank", "VxlVmskRank", 1, bytesOf(index.volume().table())});
    arrays.push_back(section(file, format::SectionId::kSurfaceMask, "smskWord", "VxlSmsk"));
    arrays.push_back(
        {"surface mask ranks", "smskRank", "VxlSmskRank", 1, bytesOf(index.surface().table())});
    arrays.push_back(section(file, format::SectionId::kSurface, "surfWord", "VxlSurf"));
    if (file.header().sphereCount > 0) {
      arrays.push_back(section(file, format::SectionId::kSpheres, "sphrWord", "VxlSphr"));
      arrays.push_back(section(file, format::SectionId::kSphereMask, "pmskWord", "VxlPmsk"));
      arrays.push_back(
          {"sphere mask ranks", "pmskRank", "VxlPmskRank", 1, bytesOf(index.spheres().table())});
      arrays.push_back(section(file, format::SectionId::kSphereRefStart, "srofWord", "VxlSrof"));
      arrays.push_back(section(file, format::SectionId::kSphereRefs, "sridWord", "VxlSrid"));
    }
    // Version 2.1 fragment lists (shaders/voxlink_scene.glsl, surfaceHit).
    if (file.surfaceMode() != format::SurfaceMode::kMean)
      arrays.push_back(section(file, format::SectionId::kFragmentStart, "frofWord", "VxlFrof"));
    if (file.surfaceMode() == format::SurfaceMode::kPlanes)
      arrays.push_back({"section FRAG", "fragEntry", "VxlFrag", 2,
                        file.sectionBytes(format::SectionId::kFragments)});
    if (file.surfaceMode() == format::SurfaceMode::kTriangles) {
      arrays.push_back(section(file, format::SectionId::kTriangleRefs, "tridWord", "VxlTrid"));
      arrays.push_back(section(file, format::SectionId::kTriangles, "trisWord", "VxlTris"));
    }
  }

  SectionBuffers out;
  out.voxelSlots_ = voxelSlots;
  out.rowApron_ = apron;
  out.rowGroups_ = groups;
  out.glsl_ = cat("// Generated by SectionBuffers::upload for ", file.path(), ".\n",
                  "// The boxes the brick index and dual box tables cover (brick_lookup.h).\n",
                  "const ivec3 kVxlIndexLo = ", ivec3Of(occupied.lo), ";\n",
                  "const ivec3 kVxlIndexSize = ", ivec3Of(occupied.size), ";\n",
                  "const ivec3 kVxlDualLo = ", ivec3Of(dual.lo), ";\n",
                  "const ivec3 kVxlDualSize = ", ivec3Of(dual.size), ";\n",
                  "// Row words hold file-wide voxel indices (row_words.h).\n",
                  "#define VXL_ROW_GLOBAL ", rowsGlobal ? 1 : 0, "\n", "#define VXL_ROW_APRON ",
                  apron ? 1 : 0, "\n", "#define VXL_ROW_GROUPS ", groups ? 1 : 0, "\n",
                  "// dualIndexWords() gives a dual brick's 8 occupied indices (brick_lookup.h).\n",
                  "#define VXL_DUAL_INDICES ", dualIndices ? 1 : 0, "\n");
  GLuint unit = options.firstUnit;
  for (const GpuArray& s : arrays) {
    const uint64_t elementBytes = 4 * s.wordsPerElement;
    const char* type = s.wordsPerElement == 4 ? "uvec4" : s.wordsPerElement == 2 ? "uvec2" : "uint";
    const GLenum format = s.wordsPerElement == 4   ? GL_RGBA32UI
                          : s.wordsPerElement == 2 ? GL_RG32UI
                                                   : GL_R32UI;
    const char* channels = s.wordsPerElement == 4 ? "" : s.wordsPerElement == 2 ? ".rg" : ".r";
    const uint64_t chunkElements = chunkWords / s.wordsPerElement;
    const int shift = std::countr_zero(chunkElements);
    const auto bytes = s.bytes;
    // Empty arrays (a file without voxels) still get one zero element: a buffer cannot be empty.
    const uint64_t elements =
        std::max<uint64_t>((bytes.size() + elementBytes - 1) / elementBytes, 1);
    const uint64_t chunks = (elements + chunkElements - 1) / chunkElements;
    std::string accessor = cat(type, " ", s.accessor, "(uint i) {\n");
    if (chunks > 1)
      accessor += cat("  uint c = i >> ", shift, "u;\n  uint j = i & ", chunkElements - 1, "u;\n");
    for (uint64_t c = 0; c < chunks; ++c) {
      // The last unit is the TF table's (volume_renderer.h).
      if (int(unit) >= maxUnits - 1)
        return makeError(ErrorCode::kTooLarge, file.path(), ": the file needs more than the ",
                         maxUnits - 1, " texture units a compute shader has for them (chunks of ",
                         limit, " bytes)");
      const uint64_t first = c * chunkElements * elementBytes;
      const uint64_t count = std::min(chunkElements, elements - c * chunkElements) * elementBytes;
      std::vector<uint8_t> staging;
      const uint64_t have =
          bytes.size() > first ? std::min<uint64_t>(bytes.size() - first, count) : 0;
      const void* data = bytes.data() + first;
      if (have < count) {  // padding the last element or an empty array
        staging.assign(count, 0u);
        std::copy_n(bytes.data() + first, have, staging.data());
        data = staging.data();
      }
      Chunk chunk{createBuffer(), createTexture(GL_TEXTURE_BUFFER), unit};
      glNamedBufferStorage(chunk.buffer.id(), GLsizeiptr(count), data, 0);
      glTextureBuffer(chunk.texture.id(), format, chunk.buffer.id());
      if (glGetError() != GL_NO_ERROR)
        return makeError(ErrorCode::kTooLarge, file.path(), ": ", s.name,
                         ": the GL refused a buffer of ", count, " bytes");
      out.gpuBytes_ += count;
      const std::string name = cat(s.block, c);
      out.glsl_ += cat("layout(binding = ", unit, ") uniform usamplerBuffer ", name, ";\n");
      const std::string fetch =
          cat("texelFetch(", name, ", int(", chunks > 1 ? "j" : "i", "))", channels);
      accessor += chunks > 1 ? cat("  if (c == ", c, "u) return ", fetch, ";\n")
                             : cat("  return ", fetch, ";\n");
      out.chunks_.push_back(std::move(chunk));
      ++unit;
    }
    if (chunks > 1) accessor += cat("  return ", type, "(0u);\n");
    out.glsl_ += accessor + "}\n";
  }
  return out;
}

void SectionBuffers::bind() const {
  for (const Chunk& c : chunks_) glBindTextureUnit(c.unit, c.texture.id());
}

}  // namespace voxlink::render::gl
