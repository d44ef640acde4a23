// SPDX-License-Identifier: BSD-3-Clause
#include "tests/readers/reader_test_util.h"

#include <zlib.h>

#include <algorithm>

namespace voxlink::sources::testing {

std::unique_ptr<VolumeSource> openOrDie(const std::string& path, const OpenOptions& options) {
  auto r = openVolume(path, options);
  EXPECT_TRUE(r) << r.message();
  if (!r) return nullptr;
  return std::move(r).value();
}

std::vector<uint8_t> readInSlabs(VolumeSource& source, uint32_t slab) {
  const VolumeInfo& info = source.info();
  std::vector<uint8_t> out(info.voxelCount() * scalarSize(info.type));
  EXPECT_TRUE(source.rewind().isOk());
  for (uint32_t z = 0; z < info.dims[2]; z += slab) {
    const uint32_t n = std::min(slab, info.dims[2] - z);
    const Status s = source.read(z, n, out.data() + uint64_t{z} * info.sliceBytes());
    EXPECT_TRUE(s.isOk()) << "slab at z " << z << ": " << (s ? "" : s.message());
    if (!s) break;
  }
  return out;
}

std::vector<uint8_t> gunzipFile(const std::string& path) {
  gzFile f = gzopen(path.c_str(), "rb");
  std::vector<uint8_t> out;
  if (!f) return out;
  std::vector<uint8_t> chunk(1 << 16);
  int n;
  while ((n = gzread(f, chunk.data(), static_cast<unsigned>(chunk.size()))) > 0)
    out.insert(out.end(), chunk.begin(), chunk.begin() + n);
  gzclose(f);
  return out;
}

std::vector<uint8_t> inflateBytes(const uint8_t* data, size_t size, size_t expectedSize) {
  std::vector<uint8_t> out(expectedSize);
  z_stream z{};
  inflateInit2(&z, 15 + 32);
  z.next_in = const_cast<Bytef*>(data);
  z.avail_in = static_cast<uInt>(size);
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(out.size());
  const int rc = inflate(&z, Z_FINISH);
  out.resize(z.total_out);
  inflateEnd(&z);
  EXPECT_EQ(rc, Z_STREAM_END);
  return out;
}

std::vector<uint8_t> gzipBytes(const std::vector<uint8_t>& data, bool gzipWrapper) {
  z_stream z{};
  deflateInit2(&z, 6, Z_DEFLATED, gzipWrapper ? 15 + 16 : 15, 8, Z_DEFAULT_STRATEGY);
  std::vector<uint8_t> out(deflateBound(&z, static_cast<uLong>(data.size())) + 32);
  z.next_in = const_cast<Bytef*>(data.data());
  z.avail_in = static_cast<uInt>(data.size());
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

void writeText(const std::string& path, const std::string& text) {
  writeBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
}

void writeWithHeader(const std::string& path, const std::string& header,
                     const std::vector<uint8_t>& data) {
  std::vector<uint8_t> all(header.begin(), header.end());
  all.insert(all.end(), data.begin(), data.end());
  writeBytes(path, all);
}

std::vector<uint8_t> patternBytes(size_t n, uint32_t seed) {
  std::vector<uint8_t> out(n);
  uint32_t x = seed * 2654435761u + 12345u;
  for (size_t i = 0; i < n; ++i) {
    x = x * 1664525u + 1013904223u;
    out[i] = static_cast<uint8_t>(x >> 24);
  }
  return out;
}

std::vector<uint8_t> bytesAfterBlankLine(const std::string& path) {
  const std::vector<uint8_t> all = readBytes(path);
  const char blank[] = "\n\n";
  auto it = std::search(all.begin(), all.end(), blank, blank + 2);
  if (it == all.end()) return {};
  return {it + 2, all.end()};
}

std::vector<uint8_t> flipZ(const std::vector<uint8_t>& data, uint64_t sliceBytes) {
  std::vector<uint8_t> out(data.size());
  const uint64_t slices = data.size() / sliceBytes;
  for (uint64_t z = 0; z < slices; ++z)
    std::copy_n(data.begin() + static_cast<long>(z * sliceBytes), sliceBytes,
                out.begin() + static_cast<long>((slices - 1 - z) * sliceBytes));
  return out;
}

std::vector<uint8_t> swapped(std::vector<uint8_t> data, size_t elementBytes) {
  for (size_t i = 0; i + elementBytes <= data.size(); i += elementBytes)
    std::reverse(data.begin() + static_cast<long>(i),
                 data.begin() + static_cast<long>(i + elementBytes));
  return data;
}

bool hasNote(const VolumeInfo& info, const std::string& fragment) {
  return std::any_of(info.notes.begin(), info.notes.end(),
                     [&](const std::string& n) { return n.find(fragment) != std::string::npos; });
}

std::string notesOf(const VolumeInfo& info) {
  std::string s;
  for (const auto& n : info.notes) s += "\n  " + n;
  return s;
}

void expectError(const Status& status, ErrorCode code,
                 std::initializer_list<std::string> fragments) {
  ASSERT_FALSE(status.isOk()) << "expected " << errorCodeName(code);
  EXPECT_EQ(status.code(), code) << errorCodeName(status.code()) << ": " << status.message();
  for (const std::string& f : fragments)
    EXPECT_NE(status.message().find(f), std::string::npos)
        << "'" << f << "' not in: " << status.message();
}

Status openAndReadAll(const std::string& path, const OpenOptions& options) {
  auto r = openVolume(path, options);
  if (!r) return r.status();
  auto data = readAll(**r);
  return data.status();
}

}  // namespace voxlink::sources::testing
