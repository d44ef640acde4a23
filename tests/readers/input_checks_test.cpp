// SPDX-License-Identifier: BSD-3-Clause
// Inputs that used to be accepted silently or to hang: non-finite origins, gzip data followed by
// garbage, Netpbm maxval 0, and FIFOs named as volumes or data files. Synthetic files only.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>

#include "tests/readers/reader_test_util.h"

namespace voxlink::sources::testing {

namespace {

std::string nrrd(const std::string& fields) { return "NRRD0004\n" + fields + "\n"; }

TEST(InputChecks, NonFiniteOriginNamesFileAndField) {
  TempDir dir;
  writeWithHeader(dir.file("o.nrrd"),
                  nrrd("type: uint8\ndimension: 3\nsizes: 2 2 2\nspace: right-anterior-superior\n"
                       "space directions: (1,0,0) (0,1,0) (0,0,1)\nspace origin: (nan,0,0)\n"
                       "encoding: raw\n"),
                  patternBytes(8));
  expectError(openVolume(dir.file("o.nrrd")), ErrorCode::kCorrupt,
              {"o.nrrd", "'space origin'", "nan"});
  writeWithHeader(dir.file("o.mha"),
                  "NDims = 3\nDimSize = 2 2 2\nOffset = 0 inf 0\nElementType = MET_UCHAR\n"
                  "ElementDataFile = LOCAL\n",
                  patternBytes(8));
  expectError(openVolume(dir.file("o.mha")), ErrorCode::kCorrupt, {"o.mha", "'Offset'", "inf"});
}

TEST(InputChecks, GzipWithTrailingGarbageIsAnError) {
  TempDir dir;
  const auto values = patternBytes(6 * 5 * 4, 3);
  auto gz = gzipBytes(values);
  const auto header = nrrd("type: uint8\ndimension: 3\nsizes: 6 5 4\nencoding: gzip\n");
  writeWithHeader(dir.file("ok.nrrd"), header, gz);
  auto ok = openOrDie(dir.file("ok.nrrd"));
  ASSERT_TRUE(ok);
  ASSERT_TRUE(readAll(*ok));
  // Zero padding after the stream is tolerated (as gzip does).
  auto padded = gz;
  padded.resize(padded.size() + 16, 0);
  writeWithHeader(dir.file("padded.nrrd"), header, padded);
  auto pad = openOrDie(dir.file("padded.nrrd"));
  ASSERT_TRUE(pad);
  EXPECT_TRUE(readAll(*pad));
  // Anything else is damage.
  auto garbage = gz;
  for (uint8_t b : {'j', 'u', 'n', 'k'}) garbage.push_back(b);
  writeWithHeader(dir.file("junk.nrrd"), header, garbage);
  auto junk = openVolume(dir.file("junk.nrrd"));
  Status status = junk ? readAll(**junk).status() : junk.status();
  expectError(status, ErrorCode::kCorrupt, {"junk.nrrd", "trailing garbage"});
}

TEST(InputChecks, NetpbmMaxvalZeroIsAnError) {
  TempDir dir;
  std::filesystem::create_directories(dir.file("stack"));
  for (int z = 0; z < 2; ++z) {
    std::string pgm = z == 1 ? "P5\n# comment\n4 3\n0\n" : "P5\n4 3\n255\n";
    pgm.append(12, '\x07');
    writeText(dir.file(cat("stack/s", z, ".pgm")), pgm);
  }
  expectError(openVolume(dir.file("stack")), ErrorCode::kCorrupt, {"s1.pgm", "'maxval'", ": 0"});
}

TEST(InputChecks, FifosFailAtOnceInsteadOfBlocking) {
  TempDir dir;
  ASSERT_EQ(mkfifo(dir.file("v.nrrd").c_str(), 0600), 0);
  expectError(openVolume(dir.file("v.nrrd")), ErrorCode::kIo, {"v.nrrd", "FIFO"});
  ASSERT_EQ(mkfifo(dir.file("v.raw").c_str(), 0600), 0);
  OpenOptions raw;
  raw.dims = std::array<uint32_t, 3>{2, 2, 2};
  raw.type = ScalarType::kU8;
  expectError(openVolume(dir.file("v.raw"), raw), ErrorCode::kIo, {"v.raw", "FIFO"});
  // A header whose detached data file is a FIFO.
  ASSERT_EQ(mkfifo(dir.file("data.raw.gz").c_str(), 0600), 0);
  writeText(
      dir.file("h.nhdr"),
      nrrd("type: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: gzip\ndata file: data.raw.gz"));
  auto h = openVolume(dir.file("h.nhdr"));
  Status status = h ? readAll(**h).status() : h.status();
  expectError(status, ErrorCode::kIo, {"data.raw.gz", "FIFO"});
}

}  // namespace
}  // namespace voxlink::sources::testing
