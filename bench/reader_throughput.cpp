// SPDX-License-Identifier: BSD-3-Clause
// Read throughput of the dense readers on the shared real files, each against a peer doing the
// same work with nothing of ours in the way: zlib's one-shot inflate of the same compressed
// bytes (already in memory) for compressed inputs, a plain ifstream read of the same bytes for
// raw inputs. Prints a table; median of 7 runs, page cache warm.
//   reader_throughput [data-dir]
#include <zlib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "sources/volume_source.h"

namespace {

using Clock = std::chrono::steady_clock;

double medianSeconds(const std::function<bool()>& run) {
  std::vector<double> times;
  for (int i = 0; i < 7; ++i) {
    const auto t0 = Clock::now();
    if (!run()) return -1;
    times.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

std::vector<uint8_t> fileBytes(const std::string& path, size_t skip = 0) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return {};
  const auto size = static_cast<size_t>(in.tellg());
  if (skip >= size) return {};
  std::vector<uint8_t> bytes(size - skip);
  in.seekg(static_cast<std::streamoff>(skip));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return bytes;
}

size_t afterBlankLine(const std::string& path) {
  const auto all = fileBytes(path);
  const char blank[] = "\n\n";
  return static_cast<size_t>(std::search(all.begin(), all.end(), blank, blank + 2) - all.begin()) +
         2;
}

bool inflateAll(const std::vector<uint8_t>& in, std::vector<uint8_t>& out) {
  z_stream z{};
  inflateInit2(&z, 15 + 32);
  z.next_in = const_cast<Bytef*>(in.data());
  z.avail_in = static_cast<uInt>(in.size());
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(out.size());
  const int rc = inflate(&z, Z_FINISH);
  inflateEnd(&z);
  return rc == Z_STREAM_END;
}

struct Input {
  const char* name;
  std::string path;
  // What the peer reads: compressed bytes to inflate, or raw files to read whole.
  std::vector<std::string> peerFiles;
  size_t peerSkip = 0;
  bool compressed = false;
};

}  // namespace

int main(int argc, char** argv) {
  const std::string data = argc > 1 ? argv[1] : VOXLINK_DATA_DIR;
  std::vector<Input> inputs = {
      {"foot NRRD (attached gzip)",
       data + "/ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd",
       {},
       0,
       true},
      {"carp NRRD (attached gzip, u16)",
       data + "/ct/openscivis_lossy/carp_128x128x256_uint16_lossy.nrrd",
       {},
       0,
       true},
      {"LIDC2 NRRD (detached gzip)",
       data + "/ct/vtkjs_LIDC2/LIDC2.nhdr",
       {data + "/ct/vtkjs_LIDC2/b1ad142a1ebc80f957fcdc329e876d51.gz"},
       0,
       true},
      {"frogtissue MetaImage (zlib)",
       data + "/volume/vtk_frogtissue/frogtissue.mhd",
       {data + "/volume/vtk_frogtissue/frogtissue.zraw"},
       0,
       true},
      {"walnut Voreen (mapped raw)",
       data + "/ct/voreen_walnut/walnut.vvd",
       {data + "/ct/voreen_walnut/walnut.raw"},
       0,
       false},
      {"headsq NRRD (93 raw files)", data + "/ct/vtk_headsq/quarter.nhdr", {}, 0, false},
      {"CT head DICOM (93 files, GDCM)", data + "/ct/slicer_CTHeadAxialDicom", {}, 0, false},
  };
  for (Input& in : inputs) {
    if (in.peerFiles.empty() && in.compressed) {
      in.peerFiles = {in.path};
      in.peerSkip = afterBlankLine(in.path);
    }
  }
  for (int i = 1; i <= 93; ++i) {
    inputs[5].peerFiles.push_back(data + "/ct/vtk_headsq/quarter." + std::to_string(i));
    inputs[6].peerFiles.push_back(data + "/ct/slicer_CTHeadAxialDicom/CTHead" + std::to_string(i) +
                                  ".dcm");
  }

  std::printf("%-32s %10s %12s %12s %8s  %s\n", "input", "MB decoded", "ours MB/s", "peer MB/s",
              "ours/peer", "peer");
  for (const Input& in : inputs) {
    auto opened = voxlink::sources::openVolume(in.path);
    if (!opened) {
      std::printf("%-32s error: %s\n", in.name, opened.message().c_str());
      continue;
    }
    auto& source = **opened;
    const auto& info = source.info();
    const uint64_t bytes = info.voxelCount() * voxlink::scalarSize(info.type);
    std::vector<uint8_t> out(bytes);
    const uint32_t slab = 16;
    const double ours = medianSeconds([&] {
      if (!source.rewind()) return false;
      for (uint32_t z = 0; z < info.dims[2]; z += slab)
        if (!source.read(z, std::min(slab, info.dims[2] - z),
                         out.data() + uint64_t{z} * info.sliceBytes()))
          return false;
      return true;
    });
    double peer = 0;
    const char* peerName = "";
    if (in.compressed) {
      const auto compressed = fileBytes(in.peerFiles[0], in.peerSkip);
      peer = medianSeconds([&] { return inflateAll(compressed, out); });
      peerName = "zlib inflate of the bytes in memory";
    } else {
      peer = medianSeconds([&] {
        for (const auto& f : in.peerFiles) {
          auto b = fileBytes(f);
          if (b.empty()) return false;
        }
        return true;
      });
      peerName = "ifstream read of the files";
    }
    const double mb = static_cast<double>(bytes) / 1e6;
    std::printf("%-32s %10.1f %12.0f %12.0f %8.2f  %s\n", in.name, mb, mb / ours, mb / peer,
                peer / ours, peerName);
  }
  return 0;
}
