// SPDX-License-Identifier: BSD-3-Clause
// `mpirun -n N voxlink convert ...` (docs/scale.md): the file N ranks write together is byte for
// byte the file one process writes, for 1 to 4 ranks, u8/u16/f32 sources, thresholds, a transfer
// function, --keep-outside, --keep-all, bricks of 8 and 16 and slice counts that do not divide.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/mpi/mpi_launch.h"
#include "tests/support/test_util.h"

namespace voxlink::testing {
namespace {

namespace fs = std::filesystem;

// A smooth field with noise: some bricks empty, some full, some partly kept.
template <class T>
std::vector<uint8_t> field(uint32_t nx, uint32_t ny, uint32_t nz, double scale, double offset) {
  std::vector<uint8_t> bytes(size_t{nx} * ny * nz * sizeof(T));
  uint32_t noise = 12345;
  T* out = reinterpret_cast<T*>(bytes.data());
  for (uint32_t z = 0; z < nz; ++z)
    for (uint32_t y = 0; y < ny; ++y)
      for (uint32_t x = 0; x < nx; ++x) {
        noise = noise * 1664525u + 1013904223u;
        const double v = std::sin(x * 0.31) * std::cos(y * 0.17) + std::sin(z * 0.23 + x * 0.05) +
                         0.25 * (noise >> 24) / 255.0;
        *out++ = static_cast<T>(v * scale + offset);
      }
  return bytes;
}

struct Case {
  const char* name;
  const char* type;
  uint32_t dims[3];
  std::vector<std::string> options;
};

const std::vector<Case>& cases() {
  static const std::vector<Case> all = {
      {"u8_threshold_b8", "u8", {37, 29, 53}, {"--threshold", "150", "--brick", "8"}},
      {"u8_threshold_b16", "u8", {37, 29, 53}, {"--threshold", "150", "--brick", "16"}},
      {"u8_tf_b8", "u8", {37, 29, 53}, {"--tf", "TF", "--brick", "8"}},
      {"u8_keepall_b16", "u8", {37, 29, 53}, {"--keep-all", "--brick", "16"}},
      {"u8_tiny_b8", "u8", {20, 20, 9}, {"--threshold", "120", "--brick", "8"}},
      {"u16_two_thresholds_b8",
       "u16",
       {45, 38, 41},
       {"--threshold", "20000,30000", "--threshold", "50000", "--brick", "8"}},
      {"u16_keep_outside_b16",
       "u16",
       {45, 38, 41},
       {"--keep-outside", "25000,40000", "--brick", "16"}},
      {"f32_threshold_b8", "f32", {33, 27, 50}, {"--threshold", "0.8", "--brick", "8"}},
      {"f32_keep_outside_axis_x_b16",
       "f32",
       {33, 27, 50},
       {"--keep-outside", "-0.5,0.5", "--mean", "0.1", "--sigma", "0.9", "--axis", "x", "--brick",
        "16"}},
  };
  return all;
}

class SameBytes : public ::testing::TestWithParam<std::tuple<size_t, int>> {};

TEST_P(SameBytes, AsOneProcess) {
  const Case& c = cases()[std::get<0>(GetParam())];
  const int ranks = std::get<1>(GetParam());
  TempDir dir;
  const std::string raw = dir.file("in.raw");
  const uint32_t* d = c.dims;
  if (std::string(c.type) == "u8") writeBytes(raw, field<uint8_t>(d[0], d[1], d[2], 60, 128));
  if (std::string(c.type) == "u16")
    writeBytes(raw, field<uint16_t>(d[0], d[1], d[2], 12000, 32000));
  if (std::string(c.type) == "f32") writeBytes(raw, field<float>(d[0], d[1], d[2], 1.0, 0.0));
  std::ofstream(dir.file("tf.json"))
      << R"({"opacity": [[100, 0], [140, 0.2], [170, 0.2], [171, 0], [200, 0], [210, 0.7]]})";
  std::vector<std::string> args = {
      "convert",   raw,
      "--dims",    std::to_string(d[0]) + "," + std::to_string(d[1]) + "," + std::to_string(d[2]),
      "--type",    c.type,
      "--slab",    "8",
      "--threads", "1"};
  for (const std::string& o : c.options) args.push_back(o == "TF" ? dir.file("tf.json") : o);
  std::vector<std::string> one = args, many = args;
  one.insert(one.end(), {"-o", dir.file("one.vxl")});
  many.insert(many.end(), {"-o", dir.file("many.vxl")});
  const Launch single = runPlain(one);
  ASSERT_EQ(single.status, 0) << single.err;
  const Launch split = runRanks(ranks, many);
  ASSERT_EQ(split.status, 0) << split.err << split.out;
  EXPECT_EQ(readBytes(dir.file("one.vxl")), readBytes(dir.file("many.vxl")))
      << c.name << " on " << ranks << " ranks";
  // Only rank 0 prints the summary.
  EXPECT_EQ(std::count(split.out.begin(), split.out.end(), '\n'), 1) << split.out;
  EXPECT_EQ(listDir(dir.path()).size(), 4u);  // no temporary left
}

std::string caseName(const ::testing::TestParamInfo<std::tuple<size_t, int>>& info) {
  return std::string(cases()[std::get<0>(info.param)].name) + "_ranks" +
         std::to_string(std::get<1>(info.param));
}

INSTANTIATE_TEST_SUITE_P(MpiConvert, SameBytes,
                         ::testing::Combine(::testing::Range(size_t{0}, cases().size()),
                                            ::testing::Values(1, 2, 3, 4)),
                         caseName);

TEST(MpiConvert, OtherCommandsRefuseSeveralRanks) {
  const Launch r = runRanks(2, {"info", VOXLINK_EXECUTABLE});  // any existing file
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.rfind("voxlink: voxlink info runs in one process", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // rank 0 alone says it
  const Launch parse = runRanks(2, {"convert", "--brick", "7"});        // an option error: once too
  EXPECT_EQ(parse.status, 2);
  EXPECT_EQ(std::count(parse.err.begin(), parse.err.end(), '\n'), 1) << parse.err;
}

}  // namespace
}  // namespace voxlink::testing
