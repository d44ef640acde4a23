// SPDX-License-Identifier: BSD-3-Clause
#include "base/crc32c.h"

#include <array>
#include <cstring>

#if defined(__x86_64__) || defined(__i386__)
#include <nmmintrin.h>
#define VOXLINK_HAVE_X86_CRC 1
#endif

namespace voxlink {
inline namespace base {
namespace {

constexpr uint32_t kPolynomial = 0x82F63B78u;  // reflected Castagnoli polynomial

using Tables = std::array<std::array<uint32_t, 256>, 8>;

constexpr Tables makeTables() {
  Tables t{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? (c >> 1) ^ kPolynomial : c >> 1;
    t[0][i] = c;
  }
  for (uint32_t i = 0; i < 256; ++i) {
    for (int s = 1; s < 8; ++s) t[s][i] = (t[s - 1][i] >> 8) ^ t[0][t[s - 1][i] & 0xFF];
  }
  return t;
}

constexpr Tables kTables = makeTables();

#ifdef VOXLINK_HAVE_X86_CRC
// One crc32 instruction takes 3 cycles but a new one can start every cycle, so the buffer is
// checksummed as three interleaved streams of kStreamBytes each and the three registers are
// joined: the register after y is run through L bytes B is Z_L(y) ^ R(0, B), where Z_L (running
// through L zero bytes) is linear in y and tabulated here byte by byte.
constexpr size_t kStreamBytes = 4096;

using ZeroShift = std::array<std::array<uint32_t, 256>, 4>;

__attribute__((target("sse4.2"))) ZeroShift makeZeroShift() {
  uint32_t basis[32];
  for (int i = 0; i < 32; ++i) {
    uint64_t c = uint32_t{1} << i;
    for (size_t k = 0; k < kStreamBytes / 8; ++k) c = _mm_crc32_u64(c, 0);
    basis[i] = static_cast<uint32_t>(c);
  }
  ZeroShift z{};
  for (int k = 0; k < 4; ++k)
    for (uint32_t b = 0; b < 256; ++b)
      for (int bit = 0; bit < 8; ++bit)
        if (b >> bit & 1) z[k][b] ^= basis[8 * k + bit];
  return z;
}

inline uint32_t zeroShift(const ZeroShift& z, uint32_t c) {
  return z[0][c & 0xFF] ^ z[1][(c >> 8) & 0xFF] ^ z[2][(c >> 16) & 0xFF] ^ z[3][c >> 24];
}

__attribute__((target("sse4.2"))) uint32_t crc32cHardware(const uint8_t* p, size_t n,
                                                          uint32_t crc) {
  uint64_t c = ~crc;
  if (n >= 3 * kStreamBytes) {
    static const ZeroShift shift = makeZeroShift();
    do {
      uint64_t a = c, b = 0, d = 0;
      for (size_t i = 0; i < kStreamBytes; i += 8) {
        uint64_t wa, wb, wd;
        std::memcpy(&wa, p + i, 8);
        std::memcpy(&wb, p + kStreamBytes + i, 8);
        std::memcpy(&wd, p + 2 * kStreamBytes + i, 8);
        a = _mm_crc32_u64(a, wa);
        b = _mm_crc32_u64(b, wb);
        d = _mm_crc32_u64(d, wd);
      }
      const uint32_t ab = zeroShift(shift, static_cast<uint32_t>(a)) ^ static_cast<uint32_t>(b);
      c = zeroShift(shift, ab) ^ static_cast<uint32_t>(d);
      p += 3 * kStreamBytes;
      n -= 3 * kStreamBytes;
    } while (n >= 3 * kStreamBytes);
  }
  while (n >= 8) {
    uint64_t word;
    std::memcpy(&word, p, 8);
    c = _mm_crc32_u64(c, word);
    p += 8;
    n -= 8;
  }
  auto c32 = static_cast<uint32_t>(c);
  while (n--) c32 = _mm_crc32_u8(c32, *p++);
  return ~c32;
}

bool cpuHasSse42() {
  static const bool has = __builtin_cpu_supports("sse4.2");
  return has;
}
#endif

}  // namespace

uint32_t crc32cPortable(const void* data, size_t size, uint32_t crc) {
  const auto* p = static_cast<const uint8_t*>(data);
  uint32_t c = ~crc;
  while (size >= 8) {
    uint32_t lo, hi;
    std::memcpy(&lo, p, 4);
    std::memcpy(&hi, p + 4, 4);
    lo ^= c;
    c = kTables[7][lo & 0xFF] ^ kTables[6][(lo >> 8) & 0xFF] ^ kTables[5][(lo >> 16) & 0xFF] ^
        kTables[4][lo >> 24] ^ kTables[3][hi & 0xFF] ^ kTables[2][(hi >> 8) & 0xFF] ^
        kTables[1][(hi >> 16) & 0xFF] ^ kTables[0][hi >> 24];
    p += 8;
    size -= 8;
  }
  while (size--) c = (c >> 8) ^ kTables[0][(c ^ *p++) & 0xFF];
  return ~c;
}

uint32_t crc32c(const void* data, size_t size, uint32_t crc) {
#ifdef VOXLINK_HAVE_X86_CRC
  if (cpuHasSse42()) return crc32cHardware(static_cast<const uint8_t*>(data), size, crc);
#endif
  return crc32cPortable(data, size, crc);
}

// zlib's crc32_combine for the Castagnoli polynomial: the register run through lengthB zero
// bytes is linear in its start value; the operator for 2^k zero bits is squared k times.
namespace {

uint32_t gf2Times(const uint32_t* matrix, uint32_t vector) {
  uint32_t sum = 0;
  for (int i = 0; vector; vector >>= 1, ++i)
    if (vector & 1) sum ^= matrix[i];
  return sum;
}

void gf2Square(uint32_t* square, const uint32_t* matrix) {
  for (int i = 0; i < 32; ++i) square[i] = gf2Times(matrix, matrix[i]);
}

}  // namespace

uint32_t crc32cCombine(uint32_t crcA, uint32_t crcB, uint64_t lengthB) {
  if (lengthB == 0) return crcA;
  uint32_t even[32], odd[32];
  odd[0] = kPolynomial;  // the operator for one zero bit
  for (int i = 1; i < 32; ++i) odd[i] = 1u << (i - 1);
  gf2Square(even, odd);  // two zero bits
  gf2Square(odd, even);  // four zero bits
  do {
    gf2Square(even, odd);  // first pass: one zero byte
    if (lengthB & 1) crcA = gf2Times(even, crcA);
    lengthB >>= 1;
    if (lengthB == 0) break;
    gf2Square(odd, even);
    if (lengthB & 1) crcA = gf2Times(odd, crcA);
    lengthB >>= 1;
  } while (lengthB != 0);
  return crcA ^ crcB;
}

}  // namespace base
}  // namespace voxlink
