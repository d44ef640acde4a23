// SPDX-License-Identifier: BSD-3-Clause
// Makes the benchmark's large inputs: reads a volume, upsamples it by an integer factor per
// axis with trilinear interpolation (cell-centred), writes a raw file slice by slice.
//   voxlink_bench_upsample INPUT FACTOR OUT.raw
#include <cmath>
#include <cstdio>
#include <vector>

#include "sources/volume_source.h"

using namespace voxlink;

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s INPUT FACTOR OUT.raw\n", argv[0]);
    return 2;
  }
  const int factor = std::atoi(argv[2]);
  auto source = sources::openVolume(argv[1]);
  if (!source) {
    std::fprintf(stderr, "%s\n", source.message().c_str());
    return 1;
  }
  const sources::VolumeInfo info = (*source)->info();
  if (info.type != ScalarType::kU8 || factor < 1) {
    std::fprintf(stderr, "%s: only u8 volumes and factors >= 1 are supported\n", argv[1]);
    return 1;
  }
  auto data = sources::readAll(**source);
  if (!data) {
    std::fprintf(stderr, "%s\n", data.message().c_str());
    return 1;
  }
  const uint32_t n[3] = {info.dims[0], info.dims[1], info.dims[2]};
  const uint32_t m[3] = {n[0] * factor, n[1] * factor, n[2] * factor};
  const uint8_t* v = data->data();
  // Source coordinate of output index i along an axis: cell centres line up.
  auto locate = [&](uint32_t i, uint32_t size, uint32_t& i0, uint32_t& i1, double& t) {
    const double f = std::max(0.0, (i + 0.5) / factor - 0.5);
    i0 = std::min(static_cast<uint32_t>(f), size - 1);
    i1 = std::min(i0 + 1, size - 1);
    t = f - i0;
  };
  FILE* out = std::fopen(argv[3], "wb");
  if (!out) {
    std::perror(argv[3]);
    return 1;
  }
  std::vector<uint8_t> slice(uint64_t{m[0]} * m[1]);
  for (uint32_t z = 0; z < m[2]; ++z) {
    uint32_t z0, z1;
    double tz;
    locate(z, n[2], z0, z1, tz);
    for (uint32_t y = 0; y < m[1]; ++y) {
      uint32_t y0, y1;
      double ty;
      locate(y, n[1], y0, y1, ty);
      const uint8_t* r00 = v + (uint64_t{z0} * n[1] + y0) * n[0];
      const uint8_t* r01 = v + (uint64_t{z0} * n[1] + y1) * n[0];
      const uint8_t* r10 = v + (uint64_t{z1} * n[1] + y0) * n[0];
      const uint8_t* r11 = v + (uint64_t{z1} * n[1] + y1) * n[0];
      for (uint32_t x = 0; x < m[0]; ++x) {
        uint32_t x0, x1;
        double tx;
        locate(x, n[0], x0, x1, tx);
        auto lerp = [&](const uint8_t* r) { return r[x0] + (r[x1] - r[x0]) * tx; };
        const double c0 = lerp(r00) + (lerp(r01) - lerp(r00)) * ty;
        const double c1 = lerp(r10) + (lerp(r11) - lerp(r10)) * ty;
        slice[uint64_t{y} * m[0] + x] = static_cast<uint8_t>(std::lround(c0 + (c1 - c0) * tz));
      }
    }
    if (std::fwrite(slice.data(), 1, slice.size(), out) != slice.size()) {
      std::perror(argv[3]);
      return 1;
    }
  }
  return std::fclose(out) == 0 ? 0 : 1;
}
