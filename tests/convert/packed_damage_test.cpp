// SPDX-License-Identifier: BSD-3-Clause
// Damaged packed files are refused with one line naming the section: flipped bytes, with and
// without matching checksums, truncation, sizes past the caller's limit, forged original tables.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "base/crc32c.h"
#include "format/voxlink_file.h"
#include "pack/packed_file.h"
#include "tests/convert/packed_fixtures.h"
#include "tests/support/test_util.h"

namespace voxlink::pack {
namespace {

using format::FileHeader;
using format::headerChecksum;
using format::kMagic;
using format::SectionEntry;
using format::SectionId;
using format::sectionName;
using test::convertReal;
using test::kFoot;
using test::Packed;
using test::packedEntry;
using test::packReal;
using test::TempDir;

// Rewrites the packed table's CRC of the section whose payload holds byte `at`, so damage
// reaches the decoder instead of being caught by the checksum.
void refreshCrc(std::vector<uint8_t>& packed, uint64_t at) {
  FileHeader h;
  std::memcpy(&h, packed.data(), sizeof h);
  for (uint32_t i = 0; i < h.sectionCount; ++i) {
    SectionEntry e;
    uint8_t* slot = packed.data() + h.sectionTableOffset + i * sizeof e;
    std::memcpy(&e, slot, sizeof e);
    if (at >= e.offset && at < e.offset + e.bytes) {
      e.crc = crc32c(packed.data() + e.offset, e.bytes);
      std::memcpy(slot, &e, sizeof e);
    }
  }
}

std::string unpackError(const std::vector<uint8_t>& packed, uint64_t maxBytes = uint64_t{1} << 32) {
  auto file = unpackFile(packed, "p.vxl", maxBytes);
  if (file) return "";
  EXPECT_EQ(file.message().find('\n'), std::string::npos) << file.message();
  return file.message();
}

TEST(PackedFile, DamageIsRefusedNamingTheSection) {
  VOXLINK_REQUIRE_DATA(kFoot);
  TempDir dir;
  const Packed p = packReal(dir, convertReal(dir, kFoot, "60"));
  for (SectionId id : {SectionId::kBrickOccupancy, SectionId::kRowMask, SectionId::kValues,
                       SectionId::kGradients, SectionId::kMeta, SectionId::kPack}) {
    SCOPED_TRACE(std::string(sectionName(id)));
    const SectionEntry e = packedEntry(p.packed, id);
    // A flipped byte: the packed payload's checksum.
    std::vector<uint8_t> damaged = p.packed;
    damaged[e.offset + e.bytes / 2] ^= 0x40;
    const std::string crc = unpackError(damaged);
    EXPECT_NE(crc.find(std::string("section ") + std::string(sectionName(id))), std::string::npos)
        << crc;
    EXPECT_NE(crc.find("checksum"), std::string::npos) << crc;
    // The same damage with the checksum made to match: the decoder or the original
    // checksums catch it.
    refreshCrc(damaged, e.offset + e.bytes / 2);
    const std::string deep = unpackError(damaged);
    EXPECT_FALSE(deep.empty()) << "damage in " << sectionName(id) << " was accepted";
  }
  // Truncation anywhere.
  for (uint64_t size :
       {uint64_t{0}, uint64_t{100}, uint64_t{256}, p.packed.size() / 2, p.packed.size() - 1}) {
    std::vector<uint8_t> cut(p.packed.begin(), p.packed.begin() + long(size));
    EXPECT_FALSE(unpackError(cut).empty()) << size;
  }
  // A file that would unpack to more than the caller allows is refused before allocating.
  EXPECT_NE(unpackError(p.packed, 1 << 20).find("PACK.originalFileBytes"), std::string::npos);
  // A section whose original bytes would be decoded over the restored section table: the file
  // would then be read through a table the packed file chose.
  {
    std::vector<uint8_t> damaged = p.packed;
    const SectionEntry pack = packedEntry(damaged, SectionId::kPack);
    uint64_t tableOffset;
    uint32_t entryCount;
    std::memcpy(&entryCount, damaged.data() + pack.offset + 4, 4);
    std::memcpy(&tableOffset, damaged.data() + pack.offset + 16, 8);
    for (uint32_t i = 0; i < entryCount; ++i) {
      uint8_t* original = damaged.data() + pack.offset + 32 + 40 * i;
      uint32_t id;
      std::memcpy(&id, original, 4);
      if (id != static_cast<uint32_t>(SectionId::kBrickOccupancy)) continue;
      const uint64_t offset = tableOffset - 64, bytes = 128;
      std::memcpy(original + 8, &offset, 8);
      std::memcpy(original + 16, &bytes, 8);
    }
    refreshCrc(damaged, pack.offset);
    const std::string overlap = unpackError(damaged);
    EXPECT_NE(overlap.find("section BOCC: original bytes"), std::string::npos) << overlap;
    EXPECT_NE(overlap.find("overlap the section table"), std::string::npos) << overlap;
  }
  // An original file larger than what its table describes, with every checksum made to match:
  // the unpacked file would end in a megabyte of zeros that nothing covers.
  {
    std::vector<uint8_t> damaged = p.packed;
    const SectionEntry pack = packedEntry(damaged, SectionId::kPack);
    uint64_t fileBytes;
    std::memcpy(&fileBytes, damaged.data() + pack.offset + 8, 8);
    fileBytes += 1 << 20;
    std::memcpy(damaged.data() + pack.offset + 8, &fileBytes, 8);
    refreshCrc(damaged, pack.offset);
    const std::string inflated = unpackError(damaged);
    EXPECT_NE(inflated.find("p.vxl: the last 1048"), std::string::npos) << inflated;
    EXPECT_NE(inflated.find("belong to no section"), std::string::npos) << inflated;
  }
  // An original file too small for its header, or a table inside the header, with every checksum
  // made to match (a PACK of one entry, the restored header's checksum recomputed): restoring the
  // header would write past the file, the table over the header.
  struct Forged {
    uint64_t fileBytes, tableOffset;
    const char* message;
  };
  for (const Forged& f :
       {Forged{32, 0, "PACK.originalFileBytes: 32 bytes cannot hold the 256-byte header"},
        Forged{255, 0, "PACK.originalFileBytes: 255 bytes cannot hold the 256-byte header"},
        Forged{4096, 0, "PACK.originalTableOffset: 0 lies inside the 256-byte header"},
        Forged{4096, 100, "PACK.originalTableOffset: 100 lies inside the 256-byte header"}}) {
    SCOPED_TRACE(f.message);
    const uint64_t fileBytes = f.fileBytes;
    std::vector<uint8_t> damaged = p.packed;
    FileHeader h;
    std::memcpy(&h, damaged.data(), sizeof h);
    SectionEntry pack;
    uint8_t* packSlot = nullptr;
    for (uint32_t i = 0; i < h.sectionCount; ++i) {
      uint8_t* slot = damaged.data() + h.sectionTableOffset + i * sizeof pack;
      std::memcpy(&pack, slot, sizeof pack);
      if (pack.id == static_cast<uint32_t>(SectionId::kPack)) {
        packSlot = slot;
        break;
      }
    }
    ASSERT_NE(packSlot, nullptr);
    uint8_t* preamble = damaged.data() + pack.offset;
    const uint32_t entryCount = 1;
    const uint64_t tableOffset = f.tableOffset;
    std::memcpy(preamble + 4, &entryCount, 4);
    std::memcpy(preamble + 8, &fileBytes, 8);
    std::memcpy(preamble + 16, &tableOffset, 8);
    FileHeader original = h;
    std::memcpy(original.magic, kMagic, sizeof original.magic);
    original.sectionTableOffset = tableOffset;
    original.sectionCount = entryCount;
    const uint32_t originalCrc = headerChecksum(original);
    std::memcpy(preamble + 24, &originalCrc, 4);
    pack.bytes = 32 + 40;
    pack.crc = crc32c(preamble, pack.bytes);
    std::memcpy(packSlot, &pack, sizeof pack);
    const std::string refused = unpackError(damaged);
    EXPECT_NE(refused.find(f.message), std::string::npos) << refused;
  }
}

}  // namespace
}  // namespace voxlink::pack
