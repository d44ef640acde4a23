// SPDX-License-Identifier: BSD-3-Clause
// The OpenVDB peer of the conversion benchmark: the same job done with OpenVDB.
// Reads a raw u8 volume, keeps voxels >= THRESHOLD as active voxels of an openvdb::FloatGrid
// (tools::copyFromDense with background 0 and tolerance THRESHOLD - 0.5), writes a
// Blosc-compressed .vdb. No gradients. Prints one line: phases, voxels, memory, file size.
//   voxlink_bench_vdb_peer IN.raw X Y Z THRESHOLD OUT.vdb
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr, "usage: %s IN.raw X Y Z THRESHOLD OUT.vdb\n", argv[0]);
    return 2;
  }
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  const int nx = std::atoi(argv[2]), ny = std::atoi(argv[3]), nz = std::atoi(argv[4]);
  const float threshold = static_cast<float>(std::atof(argv[5]));
  openvdb::initialize();
  const auto t0 = Clock::now();
  std::vector<uint8_t> data(size_t(nx) * ny * nz);
  std::ifstream in(argv[1], std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(data.size()))) {
    std::fprintf(stderr, "%s: cannot read %zu bytes\n", argv[1], data.size());
    return 1;
  }
  const auto t1 = Clock::now();
  // x varies fastest in the raw file: LayoutXYZ.
  const openvdb::CoordBBox box(openvdb::Coord(0, 0, 0), openvdb::Coord(nx - 1, ny - 1, nz - 1));
  openvdb::tools::Dense<uint8_t, openvdb::tools::LayoutXYZ> dense(box, data.data());
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  openvdb::tools::copyFromDense(dense, *grid, threshold - 0.5f);
  const auto t2 = Clock::now();
  grid->setName("density");
  openvdb::io::File file(argv[6]);
  file.setCompression(openvdb::io::COMPRESS_BLOSC);
  file.write({grid});
  file.close();
  const auto t3 = Clock::now();
  std::printf(
      "read %.3f s, copyFromDense %.3f s, write %.3f s, total %.3f s, active %llu, memUsage %llu B "
      "(%.3f B/voxel), file %llu B\n",
      seconds(t0, t1), seconds(t1, t2), seconds(t2, t3), seconds(t0, t3),
      (unsigned long long)grid->activeVoxelCount(), (unsigned long long)grid->memUsage(),
      double(grid->memUsage()) / double(grid->activeVoxelCount()),
      (unsigned long long)std::filesystem::file_size(argv[6]));
  return 0;
}
