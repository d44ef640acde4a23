// SPDX-License-Identifier: BSD-3-Clause
#include "tests/support/test_util.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <string_view>

namespace voxlink::testing {

TempDir::TempDir() {
  std::random_device rd;
  path_ = std::filesystem::temp_directory_path() /
          ("voxlink-test-" + std::to_string(getpid()) + "-" + std::to_string(rd()));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

std::vector<uint8_t> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

std::vector<std::string> listDir(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string dataDir() {
#ifdef VOXLINK_TEST_DATA_DIR
  return VOXLINK_TEST_DATA_DIR;
#else
  return "";
#endif
}

std::string dataPath(const std::string& relative) { return dataDir() + "/" + relative; }

bool dataRequired() {
  const char* value = std::getenv("VOXLINK_REQUIRE_DATA");
  return value != nullptr && std::string_view(value) == "1";
}

}  // namespace voxlink::testing
