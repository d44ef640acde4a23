// SPDX-License-Identifier: BSD-3-Clause
// CRC-32C (Castagnoli), the checksum of every VoxLink section and of the header.
// Uses the SSE4.2 crc32 instruction when the CPU has it (three interleaved streams), else
// slicing-by-8.
#pragma once

#include <cstddef>
#include <cstdint>

namespace voxlink {
inline namespace base {

// Extends `crc` (0 for a fresh checksum) over `size` bytes.
uint32_t crc32c(const void* data, size_t size, uint32_t crc = 0);

// The checksum of A followed by B from crc32c(A), crc32c(B) and B's length (O(log length)):
// what processes that each checksummed their part of a section use to checksum the whole.
uint32_t crc32cCombine(uint32_t crcA, uint32_t crcB, uint64_t lengthB);

// The portable table-driven path, exposed so tests can check the two paths agree.
uint32_t crc32cPortable(const void* data, size_t size, uint32_t crc = 0);

}  // namespace base
}  // namespace voxlink
