// SPDX-License-Identifier: BSD-3-Clause
// Writes a closed torus of about TRIANGLES triangles as a binary little-endian PLY, for the
// large-mesh stress run (bench/large_mesh_run.sh): a 10-million-triangle mesh through
// `voxlink scene build`, its time and peak memory.
//   voxlink_bench_large_mesh OUT.ply TRIANGLES
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s OUT.ply TRIANGLES\n", argv[0]);
    return 2;
  }
  const double wanted = std::atof(argv[2]);
  if (!(wanted >= 8 && wanted <= 1e9)) {
    std::fprintf(stderr, "%s: TRIANGLES must be in 8..1e9\n", argv[2]);
    return 2;
  }
  const uint32_t n = uint32_t(std::ceil(std::sqrt(wanted / 2)));  // n x n quads, 2 triangles each
  FILE* out = std::fopen(argv[1], "wb");
  if (!out) {
    std::perror(argv[1]);
    return 1;
  }
  const uint64_t vertices = uint64_t(n) * n, faces = 2ull * n * n;
  std::fprintf(out,
               "ply\nformat binary_little_endian 1.0\nelement vertex %llu\nproperty float x\n"
               "property float y\nproperty float z\nelement face %llu\n"
               "property list uchar int vertex_indices\nend_header\n",
               (unsigned long long)vertices, (unsigned long long)faces);
  const double pi = 3.14159265358979323846;
  std::vector<float> row(3 * size_t(n));
  for (uint32_t i = 0; i < n; ++i) {
    const double a = 2 * pi * i / n;
    for (uint32_t j = 0; j < n; ++j) {
      const double b = 2 * pi * j / n;
      const double r = 1.0 + 0.4 * std::cos(b);
      row[3 * j] = float(r * std::cos(a));
      row[3 * j + 1] = float(r * std::sin(a));
      row[3 * j + 2] = float(0.4 * std::sin(b));
    }
    std::fwrite(row.data(), sizeof(float), row.size(), out);
  }
  std::vector<unsigned char> face(13);
  auto put = [&](int32_t p, int32_t q, int32_t r) {
    face[0] = 3;
    std::memcpy(&face[1], &p, 4);
    std::memcpy(&face[5], &q, 4);
    std::memcpy(&face[9], &r, 4);
    std::fwrite(face.data(), 1, face.size(), out);
  };
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = 0; j < n; ++j) {
      const int32_t p = int32_t(i * n + j), q = int32_t(((i + 1) % n) * n + j),
                    r = int32_t(((i + 1) % n) * n + (j + 1) % n), s = int32_t(i * n + (j + 1) % n);
      put(p, q, r);
      put(p, r, s);
    }
  if (std::fclose(out) != 0) {
    std::perror(argv[1]);
    return 1;
  }
  std::printf("%s: torus, %llu vertices, %llu triangles\n", argv[1], (unsigned long long)vertices,
              (unsigned long long)faces);
  return 0;
}
