// SPDX-License-Identifier: BSD-3-Clause
// The VoxLink file layout, versions 1 and 2: plain structs whose every field carries its byte
// offset. Version 1 holds a sparse volume; version 2 (a scene) adds geometry to the same bricks
// and rows: surface fragments, sphere references, a material table and masks saying which
// voxels carry what. A file with volume data only is always written as version 1.
// docs/format.md is the prose spec of the same thing; the static_asserts below and
// tests/viewer/glsl_layout_test.cpp keep this header, the spec and the shaders in step.
//
// A file is: FileHeader at offset 0, then sections, each starting on a kSectionAlignment
// boundary, then the section table (SectionEntry[sectionCount]). Everything is little-endian.
// Every section is an array of 32-bit words (its byte size is padded to a multiple of 4 with
// zeros), so it can be uploaded to a GPU buffer unchanged.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "base/limits.h"

namespace voxlink::format {

inline constexpr char kMagic[8] = {'V', 'O', 'X', 'L', 'I', 'N', 'K', '\0'};
inline constexpr uint16_t kVersionMajor = 1;       // a sparse volume
inline constexpr uint16_t kVersionMajorScene = 2;  // a scene: geometry (+ volume) in one buffer
inline constexpr uint16_t kVersionMinor = 0;       // readers accept any minor version
// Version 2.1: a scene whose surface voxels also carry fragment lists (header.surfaceMode > 0).
inline constexpr uint16_t kVersionMinorFragments = 1;
// Version 2.2: plane fragments carry the box their surface piece covers (format/fragment_extent.h).
inline constexpr uint16_t kVersionMinorExtents = 2;
// Readers accept the majors they know (1 and 2) and refuse later ones: a version 1 reader would
// draw a version 2 file's geometry voxels as empty volume samples, so the major changed.
inline constexpr uint32_t kByteOrderMark = 0x01020304u;  // reads 0x04030201 when swapped
inline constexpr uint32_t kByteOrderMarkSwapped = 0x04030201u;
inline constexpr uint64_t kSectionAlignment = 64;
inline constexpr uint32_t kMinBrickSize = 4;
inline constexpr uint32_t kMaxBrickSize = 32;
// Voxel and brick indices are 32-bit on the GPU.
inline constexpr uint64_t kMaxVoxels = 0xFFFFFFFFull;
// Largest extent per axis; keeps brick counts and products far from 64-bit overflow.
inline constexpr uint32_t kMaxDim = 1u << 16;
static_assert(kMaxDim == limits::kMaxAxis,
              "base/limits.h: dense inputs take what the format holds");

enum class Axis : uint8_t { kX = 0, kY = 1, kZ = 2 };

// Codec of the GRAD section. Written to files: never renumber.
enum class GradientCodec : uint8_t {
  kPolar16 = 1,  // see format/gradient_codec.h
};

// Bits of FileHeader::flags.
enum HeaderFlags : uint32_t {
  kFlagGradientsInWorldSpace = 1u << 0,  // gradients are d(value)/d(world mm), not per index
};

struct FileHeader {             // 256 bytes at offset 0
  char magic[8];                // 8B (0)    kMagic
  uint16_t versionMajor;        // 2B (8)    kVersionMajor
  uint16_t versionMinor;        // 2B (10)   kVersionMinor
  uint32_t byteOrderMark;       // 4B (12)   kByteOrderMark
  uint32_t headerBytes;         // 4B (16)   sizeof(FileHeader)
  uint32_t headerCrc;           // 4B (20)   CRC-32C of the 256 header bytes with this field 0
  uint64_t sectionTableOffset;  // 8B (24)   byte offset of SectionEntry[sectionCount]
  uint32_t sectionCount;        // 4B (32)
  uint32_t brickSize;           // 4B (36)   n: 4, 8, 16 or 32 voxels per brick edge
  uint32_t dims[3];             // 12B (40)  voxels along x, y, z (the source's dims)
  uint32_t brickGrid[3];        // 12B (52)  ceil(dims / n) bricks along x, y, z
  uint8_t predominantAxis;      // 1B (64)   Axis along which rows run (depth axis)
  uint8_t valueType;            // 1B (65)   StoredType of the VALU section
  uint8_t gradientCodec;        // 1B (66)   GradientCodec of the GRAD section
  uint8_t sourceType;           // 1B (67)   ScalarType of the dense source
  uint32_t flags;               // 4B (68)   HeaderFlags
  double spacing[3];            // 24B (72)  world size of a voxel along x, y, z
  double origin[3];             // 24B (96)  world position of voxel (0,0,0)'s centre
  double valueScale;            // 8B (120)  source value = stored * valueScale + valueOffset
  double valueOffset;           // 8B (128)
  double valueMin;              // 8B (136)  smallest stored value, in source units
  double valueMax;              // 8B (144)  largest stored value, in source units
  double valueMaxAbsError;      // 8B (152)  max |decoded - source| over stored voxels
  double valueMaxRelError;      // 8B (160)  max |decoded - source| / |source| (source != 0)
  uint64_t voxelCount;          // 8B (168)  stored voxels
  uint64_t occupiedBrickCount;  // 8B (176)  bricks with at least one stored voxel
  double valueErrorBound;       // 8B (184)  error bound asked for, 0 if none (lossless)
  // Version 2 (scene) counts; zero in version 1, where these bytes were reserved.
  uint32_t materialCount;      // 4B (192)  entries of MATL
  uint32_t sphereCount;        // 4B (196)  entries of SPHR (0: no SPHR, SROF, SRID)
  uint64_t sphereRefCount;     // 8B (200)  entries of SRID
  uint64_t surfaceVoxelCount;  // 8B (208)  voxels whose SURF word holds a fragment
  uint64_t volumeVoxelCount;   // 8B (216)  voxels whose VMSK bit is set
  uint64_t sphereVoxelCount;   // 8B (224)  voxels whose PMSK bit is set
  // Version 2.1 (fragment lists); zero in older files, where these bytes were reserved.
  uint32_t surfaceMode;    // 4B (232)  SurfaceMode: 0 mean, 1 planes, 2 triangles
  uint32_t triangleCount;  // 4B (236)  entries of TRIS (surfaceMode 2)
  uint64_t fragmentCount;  // 8B (240)  entries of FRAG (mode 1) or TRID (mode 2)
  uint8_t reserved[8];     // 8B (248)  zero
};
static_assert(sizeof(FileHeader) == 256);
static_assert(offsetof(FileHeader, sectionTableOffset) == 24);
static_assert(offsetof(FileHeader, dims) == 40);
static_assert(offsetof(FileHeader, predominantAxis) == 64);
static_assert(offsetof(FileHeader, spacing) == 72);
static_assert(offsetof(FileHeader, valueScale) == 120);
static_assert(offsetof(FileHeader, voxelCount) == 168);
static_assert(offsetof(FileHeader, valueErrorBound) == 184);
static_assert(offsetof(FileHeader, materialCount) == 192);
static_assert(offsetof(FileHeader, sphereRefCount) == 200);
static_assert(offsetof(FileHeader, volumeVoxelCount) == 216);
static_assert(offsetof(FileHeader, sphereVoxelCount) == 224);
static_assert(offsetof(FileHeader, surfaceMode) == 232);
static_assert(offsetof(FileHeader, fragmentCount) == 240);
static_assert(offsetof(FileHeader, reserved) == 248);

// Four ASCII characters read as a little-endian u32.
constexpr uint32_t fourCC(const char (&s)[5]) {
  return uint32_t(uint8_t(s[0])) | uint32_t(uint8_t(s[1])) << 8 | uint32_t(uint8_t(s[2])) << 16 |
         uint32_t(uint8_t(s[3])) << 24;
}

// Section identifiers. A reader skips sections it does not know (they may come with a later
// minor version); every section below is required in version 1.
enum class SectionId : uint32_t {
  kMeta = fourCC("META"),            // UTF-8 JSON: source, classification, converter, notes
  kBrickOccupancy = fourCC("BOCC"),  // u32[ceil(B/32)]: bit b%32 of word b/32 = brick b occupied
  kBrickRank = fourCC("BRNK"),       // u32[ceil(B/32)]: occupied bricks before word w
  kBrickVoxelBase = fourCC("BVOX"),  // u32[K+1]: first voxel of occupied brick k; [K] = voxels
  kRowStart = fourCC("ROWS"),        // u16[K*n*n]: first voxel of row r relative to its brick
  kRowMask = fourCC("MASK"),         // u32[K*n*n*n/32]: n bits per row, bit d = voxel at depth d
  kValues = fourCC("VALU"),          // StoredType[voxels], padded to 4 bytes
  kGradients = fourCC("GRAD"),       // u16[voxels], padded to 4 bytes: GradientCodec codes
  // Version 2 (scene) sections. Each kind of content is a voxel mask (bit i%32 of word i/32 set:
  // voxel i has it) and a payload in voxel order over the voxels whose bit is set, so a kind
  // costs a bit per voxel plus its payload where it is present. A voxel's slot in a payload is
  // the rank of its bit (set bits before it); readers derive per-word prefix counts at load.
  kMaterials = fourCC("MATL"),       // MaterialRecord[materialCount]
  kVolumeMask = fourCC("VMSK"),      // u32[ceil(V/32)]: voxels with a volume sample (VALU, GRAD)
  kSurfaceMask = fourCC("SMSK"),     // u32[ceil(V/32)]: voxels with a surface fragment
  kSurface = fourCC("SURF"),         // u32[surfaceVoxelCount]: surface fragment words
  kSpheres = fourCC("SPHR"),         // SphereRecord[sphereCount]
  kSphereMask = fourCC("PMSK"),      // u32[ceil(V/32)]: voxels that reference spheres
  kSphereRefStart = fourCC("SROF"),  // u32[sphereVoxelCount+1]: slot s references
                                     //   SRID[SROF[s], SROF[s+1])
  kSphereRefs = fourCC("SRID"),      // u32[sphereRefCount]: sphere indices, ascending per voxel
  // Version 2.1: per surface voxel a list of fragments (planes) or of triangle references.
  kFragmentStart = fourCC("FROF"),  // u32[surfaceVoxelCount+1]: surface slot s has entries
                                    //   [FROF[s], FROF[s+1]) of FRAG or TRID, 1..kMaxFragments
  kFragments = fourCC("FRAG"),      // FragmentRecord[fragmentCount] (surfaceMode 1)
  kTriangleRefs = fourCC("TRID"),   // u32[fragmentCount]: triangle indices, ascending per voxel
  kTriangles = fourCC("TRIS"),      // TriangleRecord[triangleCount] (surfaceMode 2)
  // Only in packed files (pack/packed_file.h): the original table and each section's codec.
  kPack = fourCC("PACK"),
};
// (B = brick count of the grid, K = occupied bricks, n = brick size.)

inline constexpr std::array<SectionId, 8> kRequiredSections = {
    SectionId::kMeta,           SectionId::kBrickOccupancy, SectionId::kBrickRank,
    SectionId::kBrickVoxelBase, SectionId::kRowStart,       SectionId::kRowMask,
    SectionId::kValues,         SectionId::kGradients};

// Sections every version 2 file has, and those it has when sphereCount > 0. In version 2, VALU
// and GRAD hold volumeVoxelCount entries (the VMSK slots), not one per voxel.
inline constexpr std::array<SectionId, 4> kSceneSections = {
    SectionId::kMaterials, SectionId::kVolumeMask, SectionId::kSurfaceMask, SectionId::kSurface};
inline constexpr std::array<SectionId, 4> kSphereSections = {
    SectionId::kSpheres, SectionId::kSphereMask, SectionId::kSphereRefStart,
    SectionId::kSphereRefs};

inline constexpr std::array<SectionId, 2> kPlaneSections = {SectionId::kFragmentStart,
                                                            SectionId::kFragments};
inline constexpr std::array<SectionId, 3> kTriangleSections = {
    SectionId::kFragmentStart, SectionId::kTriangleRefs, SectionId::kTriangles};

std::string_view sectionName(SectionId id);  // "META", ...

// --- Version 2 records -----------------------------------------------------------------------
// A surface fragment (the paper's fragment data, section 4.1): low 16 bits the polar normal
// (GradientCodec::kPolar16, unit outward normal), high 16 bits the material index. A voxel that
// several triangles touch keeps one fragment (docs/format.md says how it is chosen).
inline constexpr uint32_t kNoSurface = 0xFFFFFFFFu;
constexpr uint32_t surfaceWord(uint16_t normalCode, uint16_t material) {
  return uint32_t{material} << 16 | normalCode;
}
constexpr uint16_t surfaceNormal(uint32_t word) { return static_cast<uint16_t>(word & 0xFFFF); }
constexpr uint16_t surfaceMaterial(uint32_t word) { return static_cast<uint16_t>(word >> 16); }
inline constexpr uint32_t kMaxMaterials = 0xFFFF;  // material 0xFFFF is never used

struct MaterialRecord {   // 64 bytes; linear RGB, every value finite
  float color[3];         // 12B (0)   diffuse colour, [0, 1]
  float opacity;          // 4B (12)   [0, 1]; 1 = opaque
  float emission[3];      // 12B (16)  >= 0, added to the shaded colour
  float reflectivity;     // 4B (28)   [0, 1]: share of a hit's light that is mirrored
  float transmission;     // 4B (32)   [0, 1]: share that is refracted
  float refractiveIndex;  // 4B (36)   >= 1 when transmission > 0
  float specular;         // 4B (40)   [0, 1]: Phong highlight strength
  float shininess;        // 4B (44)   Phong exponent, >= 0
  uint32_t reserved[4];   // 16B (48)  zero
};
static_assert(sizeof(MaterialRecord) == 64);
static_assert(offsetof(MaterialRecord, reflectivity) == 28);

struct SphereRecord {    // 32 bytes; an implicit sphere in world units
  float center[3];       // 12B (0)
  float radius;          // 4B (12)   > 0
  uint32_t material;     // 4B (16)   < materialCount
  uint32_t reserved[3];  // 12B (20)  zero
};
static_assert(sizeof(SphereRecord) == 32);

// --- Version 2.1 records: what a surface voxel holds besides its SURF word ------------------
// Written to files: never renumber. format/surface_mode.h names them for the command line.
enum class SurfaceMode : uint32_t {
  kMean = 0,       // SURF only: one fragment per voxel (version 2.0 files)
  kPlanes = 1,     // FROF + FRAG: per voxel the planes of its triangles, merged by normal
  kTriangles = 2,  // FROF + TRID + TRIS: per voxel references to the triangles themselves
};
// Longest fragment list of one voxel (FRAG or TRID entries): a longer one is refused by the
// builder and the validator.
inline constexpr uint32_t kMaxFragmentsPerVoxel = 255;
// FragmentRecord::offset is in units of 2^-12 of the voxel's smallest spacing, so planes up to
// 8 such units from the centre are held (sqrt(3)/2 for cubic voxels) and the rounding error is
// at most 2^-13 (1.2e-4) of a voxel.
inline constexpr double kPlaneOffsetUnit = 1.0 / 4096.0;

struct FragmentRecord {  // 8 bytes: one plane of a surface voxel
  uint32_t word;         // 4B (0)  surfaceWord(): polar16 unit world normal, material
  int16_t offset;        // 2B (4)  plane: dot(n, p - voxelCentre) = offset * kPlaneOffsetUnit *
                         //         min(spacing), p and the centre in world units
  uint16_t extent;       // 2B (6)  version 2.2: format/fragment_extent.h; zero (reserved) in 2.1
};
static_assert(sizeof(FragmentRecord) == 8);

struct TriangleRecord {  // 40 bytes: a triangle in world units; its normal is (b-a) x (c-a)
  float vertices[9];     // 36B (0)  a, b, c (xyz each), finite
  uint32_t material;     // 4B (36)  < materialCount
};
static_assert(sizeof(TriangleRecord) == 40);

struct SectionEntry {     // 32 bytes; the table is SectionEntry[sectionCount]
  uint32_t id;            // 4B (0)   SectionId
  uint32_t elementBytes;  // 4B (4)   size of one element: 1 (META, u8 values), 2, 4
  uint64_t offset;        // 8B (8)   byte offset from the start of the file, kSectionAlignment
  uint64_t bytes;         // 8B (16)  payload bytes, a multiple of 4 (zero padding included)
  uint32_t crc;           // 4B (24)  CRC-32C of the payload bytes
  uint32_t reserved;      // 4B (28)  zero
};
static_assert(sizeof(SectionEntry) == 32);
static_assert(offsetof(SectionEntry, offset) == 8);
static_assert(offsetof(SectionEntry, crc) == 24);
// Most table entries a reader accepts (a file has the kRequiredSections and may add others):
// a damaged sectionCount must not make the reader walk a table of billions of entries.
inline constexpr uint32_t kMaxSectionCount = 1024;

// --- Brick-local coordinates ("VoxLink space") -----------------------------------------------
// Rows run along the predominant axis a (depth axis w). The two other axes are taken in cyclic
// order: u = (a+1)%3, v = (a+2)%3, so (u, v, w) is a right-handed rotation of (x, y, z).
// Within a brick, row r = v*n + u and depth d = w, all brick-local in [0, n).
// Bricks are numbered in source order whatever the predominant axis:
//   b = (bz * brickGrid[1] + by) * brickGrid[0] + bx.
struct AxisFrame {
  int u, v, w;  // source axis index (0=x,1=y,2=z) of each VoxLink-space axis
};
constexpr AxisFrame axisFrame(Axis a) {
  const int w = static_cast<int>(a);
  return AxisFrame{(w + 1) % 3, (w + 2) % 3, w};
}

constexpr uint64_t alignUp(uint64_t value, uint64_t alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

constexpr bool isValidBrickSize(uint32_t n) { return n == 4 || n == 8 || n == 16 || n == 32; }

// Words a brick takes in the MASK section: n^3 bits.
constexpr uint32_t maskWordsPerBrick(uint32_t n) { return n * n * n / 32; }

}  // namespace voxlink::format
