// SPDX-License-Identifier: BSD-3-Clause
// Helpers shared by the test binaries.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace voxlink::testing {

// A fresh directory under the system temp dir, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

std::vector<uint8_t> readBytes(const std::string& path);
void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes);
// Files in `dir` (names only), for checking that nothing half-written was left behind.
std::vector<std::string> listDir(const std::filesystem::path& dir);

// ../shared/data as configured at build time; empty when it does not exist.
std::string dataDir();
std::string dataPath(const std::string& relative);
// VOXLINK_REQUIRE_DATA=1 in the environment (CI sets it when ../shared/data is there): a test
// whose data is missing then fails instead of skipping, so a moved file cannot hide a test.
bool dataRequired();

}  // namespace voxlink::testing

// Skips the current test when the real data set is not present (fails under dataRequired()).
#define VOXLINK_REQUIRE_DATA(relative)                                                 \
  do {                                                                                 \
    if (!std::filesystem::exists(::voxlink::testing::dataPath(relative))) {            \
      if (::voxlink::testing::dataRequired())                                          \
        FAIL() << "real data missing with VOXLINK_REQUIRE_DATA=1: "                    \
               << ::voxlink::testing::dataPath(relative);                              \
      GTEST_SKIP() << "real data missing: " << ::voxlink::testing::dataPath(relative); \
    }                                                                                  \
  } while (0)
