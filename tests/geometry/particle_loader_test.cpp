// SPDX-License-Identifier: BSD-3-Clause
// loadParticles on the PDB files in ../shared/data/particles, the text format and bad input.
#include "geometry/particle_loader.h"

#include <gtest/gtest.h>

#include "tests/support/test_util.h"

namespace voxlink::geometry {
namespace {

using testing::dataPath;
using testing::TempDir;

void writeText(const std::string& path, const std::string& text) {
  testing::writeBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
}

const std::string& elementOf(const ParticleSet& set, size_t i) {
  return set.materials[set.spheres[i].material];
}

TEST(ParticleLoader, Pdb2XHE) {
  VOXLINK_REQUIRE_DATA("particles/biopython_2XHE.pdb");
  auto set = loadParticles(dataPath("particles/biopython_2XHE.pdb"));
  ASSERT_TRUE(set) << set.message();
  ASSERT_EQ(set->spheres.size(), 6315u);
  // ATOM      1  N   HIS A   0     -16.300 -47.169   4.756  1.00117.90           N
  EXPECT_FLOAT_EQ(set->spheres[0].center[0], -16.300f);
  EXPECT_FLOAT_EQ(set->spheres[0].center[1], -47.169f);
  EXPECT_FLOAT_EQ(set->spheres[0].center[2], 4.756f);
  EXPECT_EQ(elementOf(*set, 0), "N");
  EXPECT_FLOAT_EQ(set->spheres[0].radius, 1.55f);
  EXPECT_EQ(elementOf(*set, 1), "C");
  EXPECT_FLOAT_EQ(set->spheres[1].radius, 1.70f);
  // HETATM 6317  O   HOH B2002      -4.531 -85.558  23.601  1.00 65.42           O
  EXPECT_FLOAT_EQ(set->spheres.back().center[1], -85.558f);
  EXPECT_FLOAT_EQ(set->spheres.back().radius, 1.52f);
  EXPECT_EQ(set->materials.size(), 4u);  // C N O S
}

TEST(ParticleLoader, Pdb7DDOWithZincAndAlternateLocations) {
  VOXLINK_REQUIRE_DATA("particles/biopython_7DDO.pdb");
  auto set = loadParticles(dataPath("particles/biopython_7DDO.pdb"));
  ASSERT_TRUE(set) << set.message();
  ASSERT_EQ(set->spheres.size(), 6468u);
  EXPECT_FLOAT_EQ(set->spheres[0].center[0], 102.780f);
  size_t zinc = 0;
  for (size_t i = 0; i < set->spheres.size(); ++i) {
    if (elementOf(*set, i) != "Zn") continue;
    ++zinc;
    EXPECT_FLOAT_EQ(set->spheres[i].radius, 1.39f);
  }
  EXPECT_EQ(zinc, 1u);
}

TEST(ParticleLoader, ElementFromAtomNameWhenColumnsMissing) {
  TempDir dir;
  writeText(dir.file("short.pdb"),
            "ATOM      1  CA  GLY A   1       1.000   2.000   3.000\n"
            "HETATM    2 FE   HEM A   2       4.000   5.000   6.000\n"
            "ATOM      3 HG21 THR A   3       7.000   8.000   9.000\n");
  auto set = loadPdb(dir.file("short.pdb"));
  ASSERT_TRUE(set) << set.message();
  ASSERT_EQ(set->spheres.size(), 3u);
  EXPECT_EQ(elementOf(*set, 0), "C");
  EXPECT_EQ(elementOf(*set, 1), "Fe");
  EXPECT_FLOAT_EQ(set->spheres[1].radius, kDefaultVdwRadius);  // not in Bondi's table
  EXPECT_EQ(elementOf(*set, 2), "H");                          // not mercury
  EXPECT_FLOAT_EQ(set->spheres[2].radius, 1.20f);
}

TEST(ParticleLoader, TextWithCommasCommentsAndHeader) {
  TempDir dir;
  writeText(dir.file("p.csv"),
            "# particles\nx,y,z,r,material\n1,2,3,0.5,steel\n\n 4 5 6 1.5   # no material\n"
            "7, 8, 9, 2, glass\n10 11 12 0.25 steel\n");
  auto set = loadParticles(dir.file("p.csv"));
  ASSERT_TRUE(set) << set.message();
  ASSERT_EQ(set->spheres.size(), 4u);
  EXPECT_FLOAT_EQ(set->spheres[1].center[2], 6.0f);
  EXPECT_FLOAT_EQ(set->spheres[1].radius, 1.5f);
  EXPECT_EQ(elementOf(*set, 0), "steel");
  EXPECT_EQ(elementOf(*set, 1), "default");
  EXPECT_EQ(elementOf(*set, 2), "glass");
  EXPECT_EQ(set->spheres[3].material, set->spheres[0].material);
}

struct BadCase {
  const char* name;
  const char* text;
  const char* expected;  // must appear in the message
};

TEST(ParticleLoaderErrors, OneLineWithFileAndLine) {
  const BadCase cases[] = {
      {"trunc.pdb", "REMARK x\nATOM      1  N   HIS A   0     -16.300 -47.1\n",
       "trunc.pdb: line 2"},
      {"nan.pdb",
       "ATOM      1  N   HIS A   0     -16.300     nan   4.756  1.00117.90           N\n",
       "nan.pdb: line 1: y (columns 39-46): 'nan' is not finite"},
      {"word.pdb", "ATOM      1  N   HIS A   0     -16.300  abcdef   4.756\n",
       "word.pdb: line 1: y"},
      {"none.pdb", "REMARK nothing\n", "none.pdb: no ATOM"},
      {"neg.txt", "1 2 3 1\n1 2 3 -0.5\n", "neg.txt: line 2: field 'r': -0.5"},
      {"nan.txt", "1 2 3 1\nnan 2 3 1\n", "nan.txt: line 2: field 'x'"},
      {"few.txt", "1 2 3 1\n1 2 3\n", "few.txt: line 2: 3 fields"},
      {"word.txt", "1 2 3 1\n1 two 3 1\n", "word.txt: line 2: field 'y': 'two'"},
      {"empty.txt", "# nothing\n", "empty.txt: no spheres"},
  };
  TempDir dir;
  for (const BadCase& c : cases) {
    writeText(dir.file(c.name), c.text);
    auto set = loadParticles(dir.file(c.name));
    ASSERT_FALSE(set) << c.name;
    EXPECT_NE(set.message().find(c.expected), std::string::npos) << set.message();
    EXPECT_EQ(set.message().find('\n'), std::string::npos);
  }
  auto missing = loadParticles(dir.file("missing.pdb"));
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.code(), ErrorCode::kIo);
}

}  // namespace
}  // namespace voxlink::geometry
