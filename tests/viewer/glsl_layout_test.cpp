// SPDX-License-Identifier: BSD-3-Clause
// Keeps the GLSL side in step with the C++ layout: the shaders' gradient decoder against
// format::decodeGradient, and their voxel lookups against format::VoxelLocator, for every brick
// size, predominant axis and stored type, with sections split into several buffer textures.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <random>

#include "format/gradient_codec.h"
#include "format/half.h"
#include "format/voxel_locator.h"
#include "render/brick_lookup.h"
#include "render/gl/detail/row_words.h"
#include "render/gl/detail/section_buffers.h"
#include "render/gl/detail/volume_renderer.h"
#include "render/gl/detail/voxel_words.h"
#include "render/gl/shader_program.h"
#include "render/gl/voxlink_renderer.h"
#include "tests/support/test_util.h"
#include "tests/viewer/gl_test_context.h"
#include "tests/viewer/volume_fixtures.h"

namespace voxlink::render::gl {

namespace {

// Storage-buffer bindings of the test shaders' result arrays (VXL_RESULTS_BINDING in
// shaders/test_gradient_decode.comp.glsl and shaders/test_voxel_lookup.comp.glsl).
constexpr GLuint kDecodeResultsBinding = 0;
constexpr GLuint kLookupResultsBinding = 15;

std::vector<float> gradientTableForTest() {
  std::vector<float> t;
  for (int theta = 0; theta <= format::kPolarSteps; ++theta) {
    const auto v = format::decodeGradient(uint16_t(theta << 8));
    t.push_back(v[0]);
    t.push_back(v[2]);
  }
  for (int phi = 0; phi < format::kAzimuthSteps; ++phi) {
    const auto v = format::decodeGradient(uint16_t((format::kPolarSteps / 2) << 8 | phi));
    t.push_back(v[0]);
    t.push_back(v[1]);
  }
  return t;
}

TEST(GlslLayout, GradientDecodeMatchesCppForEveryCode) {
  VOXLINK_REQUIRE_GL();
  auto program =
      ComputeProgram::build("test_gradient_decode.comp.glsl",
                            {{"VXL_GRADIENT_TABLE_BINDING", std::to_string(kGradientTableBinding)},
                             {"VXL_RESULTS_BINDING", std::to_string(kDecodeResultsBinding)}});
  ASSERT_TRUE(program) << program.message();
  const auto table = gradientTableForTest();
  GlStorageBuffer tableBuffer = createStorageBuffer(table.data(), table.size() * sizeof(float));
  GlBuffer out = createBuffer();
  glNamedBufferStorage(out.id(), 65536 * 16, nullptr, GL_MAP_READ_BIT);
  program->use();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGradientTableBinding, tableBuffer.buffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDecodeResultsBinding, out.id());
  glDispatchCompute(65536 / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<float> decoded(65536 * 4);
  glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(decoded.size() * 4), decoded.data());
  int mismatches = 0;
  for (uint32_t code = 0; code < 65536; ++code) {
    const auto cpu = format::decodeGradient(uint16_t(code));
    if (std::memcmp(cpu.data(), &decoded[code * 4], 12) != 0 && ++mismatches <= 5)
      ADD_FAILURE() << "code 0x" << std::hex << code << ": GLSL (" << decoded[code * 4] << ", "
                    << decoded[code * 4 + 1] << ", " << decoded[code * 4 + 2] << ") vs C++ ("
                    << cpu[0] << ", " << cpu[1] << ", " << cpu[2] << ")";
  }
  EXPECT_EQ(mismatches, 0);
}

struct LookupCase {
  uint32_t brick;
  format::Axis axis;
  StoredType type;
  bool rowGroups = false;  // rows with aprons as row groups (row_words.h), as on GPUs
};

class GlslLookup : public ::testing::TestWithParam<LookupCase> {};

// A file split into more chunks than the shader has texture units fails to load with a message
// naming the file and the limit, instead of rendering garbage.
TEST(GlslLayout, TooManyChunksIsAClearError) {
  VOXLINK_REQUIRE_GL();
  const DenseVolume dense = testing::makeVolume({40, 40, 40}, {1, 1, 1}, [](int x, int y, int z) {
    return (x + y + z) % 3 == 0 ? 200.0 : 0.0;
  });
  auto sparse = testing::sparsify(dense, [](double v) { return v > 0; }, {});
  ASSERT_TRUE(sparse) << sparse.message();
  voxlink::testing::TempDir dir;
  auto file = testing::writeAndOpen(*sparse, dir.file("many.vxl"));
  ASSERT_TRUE(file) << file.message();
  SectionBufferOptions tiny;
  tiny.maxChunkBytes = 64;
  auto sections = SectionBuffers::upload(*file, tiny);
  ASSERT_FALSE(sections);
  EXPECT_NE(sections.message().find("many.vxl"), std::string::npos) << sections.message();
  EXPECT_NE(sections.message().find("texture units"), std::string::npos) << sections.message();
}

TEST_P(GlslLookup, EveryCellMatchesVoxelLocator) {
  VOXLINK_REQUIRE_GL();
  const LookupCase c = GetParam();
  std::mt19937 rng(c.brick * 131 + int(c.axis) * 17 + int(c.type));
  // Dims that are multiples of no brick size; sparse random voxels plus a solid block.
  const DenseVolume dense = testing::makeVolume({37, 21, 50}, {1, 1, 1}, [&](int x, int y, int z) {
    if (x >= 3 && x < 12 && y >= 2 && y < 9 && z >= 30 && z < 41) return 200.0;
    return (rng() % 9 == 0) ? double(1 + rng() % 250) : 0.0;
  });
  testing::SparseOptions o;
  o.brickSize = c.brick;
  o.axis = c.axis;
  o.type = c.type;
  auto sparse = testing::sparsify(
      dense, [](double v) { return v > 0; }, o);
  ASSERT_TRUE(sparse) << sparse.message();
  voxlink::testing::TempDir dir;
  auto file = testing::writeAndOpen(*sparse, dir.file("lookup.vxl"));
  ASSERT_TRUE(file) << file.message();

  // Split the larger sections into two or three chunks: the chunked accessors get used.
  uint64_t largest = 0;
  for (const auto& e : file->sectionTable()) largest = std::max(largest, e.bytes);
  SectionBufferOptions split;
  split.maxChunkBytes = std::max<uint64_t>(largest / 2, 64);
  split.rowGroups =
      c.rowGroups ? SectionBufferOptions::RowGroups::kOn : SectionBufferOptions::RowGroups::kOff;
  auto sections = SectionBuffers::upload(*file, split);
  ASSERT_TRUE(sections) << sections.message();
  // 6 arrays (with the dual brick indices), one more with VALU (values wider than 8 bits,
  // voxel_words.h), one more with MASK and ROWS in place of row words (32^3 bricks, row_words.h).
  const uint32_t unsplit = 6u + (storedSize(c.type) == 1 ? 0u : 1u) + (c.brick > 16 ? 1u : 0u);
  EXPECT_GT(sections->bindingCount(), unsplit) << "no section was split";

  auto defines = voxlinkDefines(file->header());
  defines.push_back({"VXL_RESULTS_BINDING", std::to_string(kLookupResultsBinding)});
  auto program = ComputeProgram::build("test_voxel_lookup.comp.glsl", defines,
                                       {{"voxlink_sections.glsl", sections->glsl()}});
  ASSERT_TRUE(program) << program.message();
  const auto& d = dense.dims;
  const uint32_t total = d[0] * d[1] * d[2];
  GlBuffer out = createBuffer();
  glNamedBufferStorage(out.id(), GLsizeiptr(total) * 16, nullptr, GL_MAP_READ_BIT);
  program->use();
  sections->bind();
  glUniform3i(program->uniform("uDims"), GLint(d[0]), GLint(d[1]), GLint(d[2]));
  glUniform3i(program->uniform("uBrickGrid"), GLint(file->header().brickGrid[0]),
              GLint(file->header().brickGrid[1]), GLint(file->header().brickGrid[2]));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLookupResultsBinding, out.id());
  glDispatchCompute((total + 63) / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<int32_t> results(size_t(total) * 4);
  glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(results.size() * 4), results.data());

  const bool apron = sections->glsl().find("#define VXL_ROW_APRON 1") != std::string::npos;
  EXPECT_EQ(apron, c.brick <= 8 && storedSize(c.type) == 1);
  EXPECT_EQ(sections->rowGroups(), apron && c.rowGroups);
  const format::VoxelLocator locator(*file);
  const size_t valueSize = storedSize(c.type);
  const uint8_t* values = file->valueBytes();
  const auto codes = file->gradientCodes();
  const int w = int(c.axis);
  int errors = 0;
  for (uint32_t z = 0; z < d[2]; ++z)
    for (uint32_t y = 0; y < d[1]; ++y)
      for (uint32_t x = 0; x < d[0]; ++x) {
        const int32_t* r = &results[size_t(dense.index(x, y, z)) * 4];
        const int64_t expected = locator.find(x, y, z);
        uint32_t bits = 0;
        if (expected >= 0) std::memcpy(&bits, values + expected * valueSize, valueSize);
        // The next stored voxel along w within the same brick row.
        int64_t next = -1;
        if (expected >= 0) {
          uint32_t p[3] = {x, y, z};
          const uint32_t end = std::min((p[w] / c.brick + 1) * c.brick, d[w]);
          for (uint32_t q = p[w] + 1; q < end && next < 0; ++q) {
            p[w] = q;
            next = locator.find(p[0], p[1], p[2]);
          }
          if (next >= 0) {
            EXPECT_EQ(next, expected + 1) << "the next list element is not index + 1";
          }
        }
        // With row aprons (row_words.h) the shader's indices count the copied voxel words too:
        // the same voxel (value and direction), and the next one in the row right after it.
        const bool sameVoxel = apron ? (r[0] >= 0) == (expected >= 0) : r[0] == expected;
        const bool sameNext = apron ? (next < 0 ? r[3] == -1 : r[3] == r[0] + 1) : r[3] == next;
        const bool ok = sameVoxel && uint32_t(r[1]) == bits &&
                        (expected < 0 ||
                         uint32_t(r[2]) == render::gl::packGradientDirection(codes[expected])) &&
                        sameNext;
        if (!ok && ++errors <= 5)
          ADD_FAILURE() << "cell (" << x << ", " << y << ", " << z << "): GLSL voxel " << r[0]
                        << " bits " << r[1] << " code " << r[2] << " next " << r[3]
                        << "; C++ voxel " << expected << " bits " << bits << " next " << next;
      }
  EXPECT_EQ(errors, 0);
}

// The packed directions the shaders read instead of codes, used without normalizing: within
// 0.4 degrees of the decoded code and of unit length to within 1 %, zero for the zero-gradient
// code.
TEST(VoxelWords, DirectionsWithinFourTenthsOfADegree) {
  EXPECT_EQ(render::gl::packGradientDirection(format::kZeroGradient), 0u);
  double worst = 0, worstLength = 0;
  for (uint32_t code = 0; code < (1u << 16); ++code) {
    const auto v = format::decodeGradient(uint16_t(code));
    if (v[0] == 0 && v[1] == 0 && v[2] == 0) continue;
    const uint32_t w = render::gl::packGradientDirection(uint16_t(code));
    ASSERT_EQ(w >> 24, 0u);
    double u[3], length = 0, dot = 0;
    for (int a = 0; a < 3; ++a) {
      const int32_t bits = int32_t(w >> (8 * a) & 0xFFu);
      u[a] = (bits >= 128 ? bits - 256 : bits) / 127.0;
      length += u[a] * u[a];
    }
    length = std::sqrt(length);
    for (int a = 0; a < 3; ++a) dot += u[a] / length * v[a];
    worst = std::max(worst, std::acos(std::min(dot, 1.0)) * 180 / M_PI);
    worstLength = std::max(worstLength, std::fabs(length - 1));
  }
  EXPECT_LT(worst, 0.4);
  EXPECT_GT(worst, 0.0);  // the rounding is real: this test would notice a lossless change
  EXPECT_LT(worstLength, 0.01);
}

// 8-bit values ride in the top byte of their voxel's word; without values it stays 0.
TEST(VoxelWords, EightBitValuesInTheTopByte) {
  const uint8_t codes[] = {0x34, 0x12, 0xCD, 0xAB};
  const uint8_t values[] = {7, 255};
  const auto words = render::gl::packVoxelWords(codes, values);
  ASSERT_EQ(words.size(), 2u);
  EXPECT_EQ(words[0], render::gl::packGradientDirection(0x1234) | 7u << 24);
  EXPECT_EQ(words[1], render::gl::packGradientDirection(0xABCD) | 255u << 24);
  const auto bare = render::gl::packVoxelWords(codes, {});
  EXPECT_EQ(bare[1], render::gl::packGradientDirection(0xABCD));
}

TEST(RowWords, FileWideStartsAddTheBricksFirstVoxel) {
  // Two 4^3 bricks: 16 rows of 4 bits each, two MASK words per brick.
  const uint32_t masks[] = {0x0000000Bu, 0, 0x00000001u, 0};
  std::vector<uint16_t> starts(32, 0);
  starts[1] = 3;   // brick 0, row 1: after the 3 voxels of row 0
  starts[17] = 1;  // brick 1, row 1
  const uint32_t first[] = {0, 4};
  const auto local = packRowWords(4, 2, masks, starts);
  const auto global = packRowWords(4, 2, masks, starts, first);
  EXPECT_EQ(local[0], 0xBu);
  EXPECT_EQ(global[0], 0xBu);
  EXPECT_EQ(local[1], 3u << 4);
  EXPECT_EQ(global[1], 3u << 4);
  EXPECT_EQ(local[16], 1u);
  EXPECT_EQ(global[16], 1u | 4u << 4);
  EXPECT_EQ(global[17], (4u + 1u) << 4);
  EXPECT_TRUE(rowWordsGlobal(8, (1u << 24) - 1));
  EXPECT_FALSE(rowWordsGlobal(8, 1u << 24));
  EXPECT_FALSE(rowWordsGlobal(16, 100));
}

// Row aprons: a row's word shows (bit n) whether the brick next along w holds its depth-0
// voxel, whose word is copied after the row's own; starts index the words with the copies.
TEST(RowWords, ApronCopiesTheNextBricksFirstVoxel) {
  // Two 4^3 bricks, brick 1 next to brick 0 along w. Brick 0: row 0 holds depths 0, 1, 3; row 1
  // depth 3. Brick 1: row 0 holds depth 0, row 1 depth 2 (no apron for brick 0's row 1).
  const uint32_t masks[] = {0x0000008Bu, 0, 0x00000041u, 0};
  std::vector<uint16_t> starts(32, 0);
  starts[1] = 3;
  starts[17] = 1;
  const uint32_t first[] = {0, 4};
  const uint32_t words[] = {10, 11, 13, 23, 40, 42};  // file order: brick 0's 4, brick 1's 2
  const uint32_t next[] = {1, kEmptyBrick};
  const ApronRows rows = packApronRows(4, 2, masks, starts, first, words, next);
  EXPECT_EQ(rows.rowWords[0], 0xBu | 1u << 4);   // apron: brick 1 row 0 depth 0
  EXPECT_EQ(rows.rowWords[1], 0x8u | 4u << 5);   // after 3 voxels and the copy
  EXPECT_EQ(rows.rowWords[16], 0x1u | 5u << 5);  // brick 1 has no brick next along w
  EXPECT_EQ(rows.rowWords[17], 0x4u | 6u << 5);
  EXPECT_EQ(rows.voxelWords, (std::vector<uint32_t>{10, 11, 13, 40, 23, 40, 42}));
  // Row groups (4 rows each: masks of rows 0-2 and their aprons in word 0, row 3's word with row
  // 0's start in word 1) give back every row word.
  const std::vector<uint32_t> groups = packRowGroups(4, rows.rowWords);
  ASSERT_EQ(groups.size(), 16u);
  EXPECT_EQ(groups[0], 0xBu | 0x8u << 4 | 1u << 12);  // rows 0 and 1, row 0's apron
  EXPECT_EQ(groups[1], 0u);
  EXPECT_EQ(groups[3], 5u << 5);  // rows 4-7 after 4 voxels and a copy
  for (uint64_t r = 0; r < rows.rowWords.size(); ++r)
    EXPECT_EQ(rowWordOfGroups(4, groups, r), rows.rowWords[r]) << "row " << r;
  EXPECT_TRUE(rowWordsApronFit(8, (1u << 23) - 1001, 1000));
  EXPECT_FALSE(rowWordsApronFit(8, 1u << 23, 0));
  EXPECT_FALSE(rowWordsApronFit(16, 100, 100));
}

// Row groups of 8^3 bricks (rows 0-2's masks fill 24 bits of word 0) give back every row word,
// at random occupancy with aprons between bricks 0 -> 1 -> 2.
TEST(RowWords, GroupsGiveBackEveryRowWordOfEightCubedBricks) {
  std::mt19937 rng(7);
  const uint32_t n = 8, bricks = 3;
  std::vector<uint32_t> masks(bricks * 16);
  for (uint32_t& m : masks) m = rng() & rng();  // about a quarter of the voxels
  std::vector<uint16_t> starts(bricks * 64);
  std::vector<uint32_t> first(bricks);
  uint32_t voxels = 0;
  for (uint32_t k = 0; k < bricks; ++k) {
    first[k] = voxels;
    for (uint32_t row = 0; row < 64; ++row) {
      starts[k * 64 + row] = uint16_t(voxels - first[k]);
      voxels += uint32_t(std::popcount((masks[k * 16 + row / 4] >> (8 * (row % 4))) & 0xFFu));
    }
  }
  std::vector<uint32_t> words(voxels);
  for (uint32_t i = 0; i < voxels; ++i) words[i] = i * 3 + 1;
  const uint32_t next[] = {1, 2, kEmptyBrick};
  const ApronRows rows = packApronRows(n, bricks, masks, starts, first, words, next);
  const std::vector<uint32_t> groups = packRowGroups(n, rows.rowWords);
  ASSERT_EQ(groups.size(), bricks * 16u * 2u);  // 8 bytes per 4 rows
  int aprons = 0;
  for (uint64_t r = 0; r < rows.rowWords.size(); ++r) {
    aprons += int((rows.rowWords[r] >> n) & 1u);
    ASSERT_EQ(rowWordOfGroups(n, groups, r), rows.rowWords[r]) << "row " << r;
  }
  EXPECT_GT(aprons, 10);
}

std::vector<LookupCase> lookupCases() {
  std::vector<LookupCase> cases;
  for (uint32_t brick : {4u, 8u, 16u, 32u})
    for (format::Axis axis : {format::Axis::kX, format::Axis::kY, format::Axis::kZ})
      cases.push_back({brick, axis, brick == 8 ? StoredType::kU16 : StoredType::kU8});
  // Row groups of 4^3 and 8^3 bricks (one and two groups per mask word).
  for (format::Axis axis : {format::Axis::kX, format::Axis::kY, format::Axis::kZ}) {
    cases.push_back({4, axis, StoredType::kU8, true});
    cases.push_back({8, axis, StoredType::kU8, true});
  }
  cases.push_back({8, format::Axis::kZ, StoredType::kU8});  // row words of 8^3 bricks
  cases.push_back({8, format::Axis::kZ, StoredType::kF16});
  cases.push_back({8, format::Axis::kY, StoredType::kF32});
  return cases;
}

std::string lookupName(const ::testing::TestParamInfo<LookupCase>& param) {
  std::string name = "n";
  name += std::to_string(param.param.brick);
  name += "_axis";
  name.push_back("xyz"[int(param.param.axis)]);
  name += "_";
  name += storedName(param.param.type);
  if (param.param.rowGroups) name += "_groups";
  return name;
}

INSTANTIATE_TEST_SUITE_P(AllLayouts, GlslLookup, ::testing::ValuesIn(lookupCases()), lookupName);

}  // namespace
}  // namespace voxlink::render::gl
