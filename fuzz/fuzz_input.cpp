// SPDX-License-Identifier: BSD-3-Clause
#include "fuzz/fuzz_input.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <system_error>

namespace voxlink::fuzz {
namespace {

constexpr std::string_view kMarkerStart = "\n==> ";
constexpr std::string_view kMarkerEnd = " <==\n";
constexpr size_t kMaxFiles = 64;
constexpr size_t kMaxName = 64;
// Slices are read into one buffer of at most this many bytes.
constexpr uint64_t kReadCap = uint64_t{16} << 20;

bool goodName(std::string_view name) {
  if (name.empty() || name.size() > kMaxName || name == "." || name == "..") return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
           c == '_' || c == '-';
  });
}

}  // namespace

std::vector<FuzzFile> splitFuzzFiles(std::span<const uint8_t> input, std::string mainName) {
  const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
  std::vector<FuzzFile> files;
  std::string name = std::move(mainName);
  size_t start = 0, from = 0;
  while (files.size() + 1 < kMaxFiles) {
    const size_t marker = text.find(kMarkerStart, from);
    if (marker == std::string_view::npos) break;
    const size_t nameBegin = marker + kMarkerStart.size();
    const size_t end = text.find(kMarkerEnd, nameBegin);
    if (end == std::string_view::npos) break;
    const std::string_view next = text.substr(nameBegin, end - nameBegin);
    if (!goodName(next)) {
      from = nameBegin;
      continue;
    }
    files.push_back({name, input.subspan(start, marker - start)});
    name = std::string(next);
    start = end + kMarkerEnd.size();
    from = start;
  }
  files.push_back({name, input.subspan(start)});
  return files;
}

ScratchDir::ScratchDir() {
  // tmpfs when there is one: a run writes its files every time.
  std::string base = std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
  if (const char* tmp = std::getenv("VOXLINK_FUZZ_TMPDIR")) base = tmp;
  std::string pattern = base + "/voxlink-fuzz-XXXXXX";
  if (!mkdtemp(pattern.data())) std::abort();  // no scratch space: nothing can run
  path_ = pattern;
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

void ScratchDir::clear() {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(path_, ec))
    std::filesystem::remove_all(entry.path(), ec);
}

std::string ScratchDir::write(const std::vector<FuzzFile>& files) {
  clear();
  for (const FuzzFile& f : files) {
    std::ofstream out(path_ / f.name, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(f.bytes.data()),
              static_cast<std::streamsize>(f.bytes.size()));
  }
  return (path_ / files.front().name).string();
}

ScratchDir& scratch() {
  static ScratchDir dir;
  return dir;
}

Status drainVolume(sources::VolumeSource& source) {
  const sources::VolumeInfo& info = source.info();
  const uint64_t sliceBytes = info.sliceBytes();
  const uint32_t depth = info.dims[2];
  if (sliceBytes == 0 || depth == 0 || sliceBytes > kReadCap) return Status::ok();
  const uint64_t fit = std::min<uint64_t>(depth, kReadCap / sliceBytes);
  std::vector<uint8_t> buffer(fit * sliceBytes);
  // In slabs of up to 4 slices, as a converter would read them.
  const uint32_t slab = static_cast<uint32_t>(std::min<uint64_t>(fit, 4));
  for (uint32_t z = 0; z < fit; z += slab) {
    const uint32_t count = static_cast<uint32_t>(std::min<uint64_t>(slab, fit - z));
    VOXLINK_RETURN_IF_ERROR(source.read(z, count, buffer.data() + (z * sliceBytes)));
  }
  // The zero-copy path serves the same bytes straight from a mapping.
  if (const auto* mapped = static_cast<const volatile uint8_t*>(source.map(0, 1))) {
    (void)mapped[0];
    (void)mapped[sliceBytes - 1];
    source.unmap(0, 1);
  }
  if (fit < depth && source.randomAccess())
    VOXLINK_RETURN_IF_ERROR(source.read(depth - 1, 1, buffer.data()));
  VOXLINK_RETURN_IF_ERROR(source.rewind());
  return source.read(0, 1, buffer.data());
}

}  // namespace voxlink::fuzz
