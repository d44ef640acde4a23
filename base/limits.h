// SPDX-License-Identifier: BSD-3-Clause
// Every size limit VoxLink applies to input, named once. Files and command lines are checked
// against these before anything is allocated; docs/reliability.md lists them with the reason.
// The limits of the .vxl layout itself (brick sizes, 2^32 stored voxels, 2^16 voxels per axis)
// are part of the format and live in format/layout.h.
#pragma once

#include <cstddef>
#include <cstdint>

namespace voxlink {
inline namespace base {
namespace limits {

// Voxels along one axis of any dense input; the .vxl format's own per-axis limit (format::kMaxDim,
// which format/layout.h asserts equal), so `stats` and `convert` accept the same inputs.
inline constexpr uint64_t kMaxAxis = uint64_t{1} << 16;
// Voxels of any dense input (2^40): hostile headers fail before allocating.
inline constexpr uint64_t kMaxVoxels = uint64_t{1} << 40;
// Bytes of a file that a reader holds in memory whole (VTK XML image data).
inline constexpr uint64_t kMaxWholeFileBytes = uint64_t{4} << 30;
// Compressed blocks in one VTK XML data array.
inline constexpr uint64_t kMaxVtiBlocks = uint64_t{1} << 24;
// zlib cannot expand data by more than about 1032:1; a block that claims more is corrupt.
inline constexpr uint64_t kMaxZlibRatio = 1032;
// Data files a numbered list (NRRD `data file: s%d.raw 1 93 1`, MetaImage) may name.
inline constexpr uint64_t kMaxListedFiles = 1'000'000;
// Bytes of a text header (NRRD, MetaImage).
inline constexpr size_t kMaxTextHeaderBytes = size_t{1} << 20;
// Bytes of a .vvd header (histograms and previews make them big).
inline constexpr size_t kMaxVvdHeaderBytes = size_t{16} << 20;
// Bytes of a transfer function JSON file.
inline constexpr uint64_t kMaxTransferFunctionBytes = uint64_t{64} << 20;

// Bytes a packed .vxl may unpack to in memory (pack/packed_file.h). A few bytes of zstd can
// stand for gigabytes, so the size the file claims is checked against this before allocating.
inline constexpr uint64_t kMaxUnpackedBytes = uint64_t{64} << 30;

// Threads any part of the toolkit starts for one task (`--threads`, Python's `threads=`). More
// is a mistake (a typo, -1 read as unsigned), not a machine: each thread holds a stack and a
// kernel task, and a request for 100000 exhausted this machine's tasks before the first ran.
inline constexpr unsigned kMaxThreads = 1024;

// Histogram bins `voxlink stats --bins` prints, one line each: more is a typo (2^32 - 1 bins ran
// out of memory; 10^8 wrote 6.4 GB of text about a 512-byte file).
inline constexpr uint32_t kMaxHistogramBins = uint32_t{1} << 20;

// Memory the GDCM guard's child may use reading a DICOM series, on top of twice its largest file
// (sources/readers/gdcm_guard.cpp): damaged files can make GDCM allocate gigabytes.
inline constexpr uint64_t kMaxGdcmProbeBytes = uint64_t{2} << 30;

}  // namespace limits
}  // namespace base
}  // namespace voxlink
