// SPDX-License-Identifier: BSD-3-Clause
#include "pack/packed_file.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>

#include "base/crc32c.h"
#include "base/output_file.h"
#include "base/parallel_for.h"
#include "format/derived_sections.h"
#include "format/validator.h"
#include "pack/detail/gradient_predictor.h"

namespace voxlink::pack {

using format::alignUp;
using format::checkHeader;
using format::deriveBrickVoxelBase;
using format::deriveRowStarts;
using format::FileHeader;
using format::headerChecksum;
using format::kMagic;
using format::kMaxSectionCount;
using format::kSectionAlignment;
using format::rowStartsMatch;
using format::sampleSlots;
using format::sectionChecksums;
using format::SectionEntry;
using format::SectionId;
using format::sectionName;
using format::validateStructure;
using format::VoxLinkFile;

namespace {

// Fuzzing builds skip the checksums of the packed payloads and header, which a mutated input
// never matches, so the fuzzer reaches the decoders; the original sections' checksums, checked
// after decoding, stay.
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
constexpr bool kCheckPackedChecksums = false;
#else
constexpr bool kCheckPackedChecksums = true;
#endif

struct PackPreamble {  // 32 bytes at the start of PACK
  uint32_t version;
  uint32_t entryCount;  // original sections
  uint64_t originalFileBytes;
  uint64_t originalTableOffset;
  uint32_t originalHeaderCrc;
  uint32_t chunkBytes;  // kPackChunkBytes
};
static_assert(sizeof(PackPreamble) == 32);

struct PackEntry {  // 40 bytes per original section, in the original table's order
  SectionEntry original;
  uint32_t codec;  // SectionCodec
  uint32_t reserved;
};
static_assert(sizeof(PackEntry) == 40);

std::string nameOf(uint32_t id) { return std::string(sectionName(static_cast<SectionId>(id))); }

// How each section is encoded: gradients against their prediction, row starts and brick bases
// derived from the masks (when they match), sections of slowly changing numbers (values) as
// deltas, the rest as they are.
SectionCodec codecFor(SectionId id, const PackOptions& options) {
  switch (id) {
    case SectionId::kGradients:
      return options.predictGradients ? SectionCodec::kGradientResidualPortable
                                      : SectionCodec::kDeltaZstd;
    case SectionId::kRowStart:
    case SectionId::kBrickVoxelBase:
      return SectionCodec::kDerived;
    case SectionId::kValues:
    case SectionId::kSphereRefStart:
    case SectionId::kFragmentStart:
      return SectionCodec::kDeltaZstd;
    default:
      return SectionCodec::kZstd;
  }
}

GradientPrediction predictionOf(SectionCodec codec) {
  return codec == SectionCodec::kGradientResidual ? GradientPrediction::kExact
                                                  : GradientPrediction::kPortable;
}

struct FreeDeleter {  // for calloc'ed blocks
  void operator()(void* p) const { std::free(p); }
};

// Computes a derived section (ROWS or BVOX) from `masks` into `out`.
Status derive(SectionId id, std::span<const uint8_t> masks, uint32_t brickSize,
              std::span<uint8_t> out, const std::string& where, unsigned threads) {
  if (id == SectionId::kRowStart) return deriveRowStarts(masks, brickSize, out, where, threads);
  if (id == SectionId::kBrickVoxelBase) return deriveBrickVoxelBase(masks, brickSize, out, where);
  return makeError(ErrorCode::kCorrupt, where, ": only ROWS and BVOX can be derived");
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

bool isPackedFile(std::span<const uint8_t> bytes) {
  return bytes.size() >= sizeof(kPackedMagic) &&
         std::memcmp(bytes.data(), kPackedMagic, sizeof(kPackedMagic)) == 0;
}

Result<PackReport> packFile(const VoxLinkFile& file, const std::string& path,
                            const PackOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  VOXLINK_RETURN_IF_ERROR(checkThreadCount(options.threads, "--threads"));
  VOXLINK_RETURN_IF_ERROR(checkOutputTarget(path, {file.path()}));
  PackReport report;
  report.inputBytes = file.fileBytes();
  const unsigned workers = threadCount(options.threads);
  const auto& table = file.sectionTable();
  std::vector<std::vector<uint8_t>> payloads(table.size());
  std::vector<PackEntry> entries(table.size());
  const std::span<const uint8_t> masks = file.sectionBytes(SectionId::kRowMask);
  // Sections share 95 % of the bar by their bytes; writing the file is the rest.
  uint64_t totalBytes = 0, doneBytes = 0;
  for (const SectionEntry& e : table) totalBytes += e.bytes;
  reportProgress(options.progress, 0, "packing");
  for (size_t i = 0; i < table.size(); ++i) {
    const SectionEntry& e = table[i];
    const auto id = static_cast<SectionId>(e.id);
    SectionCodec codec = codecFor(id, options);
    const std::span<const uint8_t> raw = file.sectionBytes(e);
    if (codec == SectionCodec::kDerived) {
      // Stored only if the masks do not give these very bytes.
      const uint32_t n = file.header().brickSize;
      bool same;
      if (id == SectionId::kRowStart) {
        same = rowStartsMatch(masks, n, raw, options.threads);
      } else {
        std::vector<uint8_t> derived(raw.size());
        same = derive(id, masks, n, derived, path, options.threads).isOk() &&
               (raw.empty() || std::memcmp(derived.data(), raw.data(), raw.size()) == 0);
      }
      codec = same ? SectionCodec::kDerived : SectionCodec::kDeltaZstd;
    }
    // GRAD's predictions are made chunk by chunk as the workers encode them: no buffer of
    // them as large as GRAD, and each chunk's are still in the cache when they are subtracted.
    std::optional<GradientRangePredictor> predictor;
    std::atomic<uint64_t> predictNanoseconds{0};  // summed over the workers
    CodePrediction prediction;
    if (isGradientResidual(codec)) {
      const auto predictStart = std::chrono::steady_clock::now();
      predictor.emplace(file, predictionOf(codec));
      report.predictSeconds += secondsSince(predictStart);
      prediction.count = sampleSlots(file.header());
      prediction.fill = [&](uint64_t first, std::span<uint16_t> out) {
        const auto chunkStart = std::chrono::steady_clock::now();
        predictor->predict(first, out);
        predictNanoseconds += static_cast<uint64_t>(secondsSince(chunkStart) * 1e9);
      };
    }
    if (codec != SectionCodec::kDerived) {
      auto encoded =
          encodeSection(raw, e.elementBytes, codec, options.level, options.threads, prediction);
      // (wall-clock time: the workers' time over the number of them that had a chunk)
      const uint64_t chunks = (raw.size() + kPackChunkBytes - 1) / kPackChunkBytes;
      report.predictSeconds += predictNanoseconds / 1e9 / std::clamp<uint64_t>(chunks, 1, workers);
      if (!encoded)
        return makeError(encoded.code(), path, ": section ", sectionName(id), ": ",
                         encoded.message());
      payloads[i] = std::move(*encoded);
      if (payloads[i].size() >= e.bytes && !isGradientResidual(codec)) {
        codec = SectionCodec::kStored;  // incompressible (or tiny): kept as it is
        payloads[i].assign(raw.begin(), raw.end());
      }
    }
    entries[i] = PackEntry{e, static_cast<uint32_t>(codec), 0};
    report.sections.push_back({id, codec, e.bytes, payloads[i].size()});
    doneBytes += e.bytes;
    reportProgress(options.progress,
                   0.95 * double(doneBytes) / double(std::max<uint64_t>(1, totalBytes)), "packing");
  }
  // Layout: header, payloads (64-byte aligned), PACK, table.
  const FileHeader& original = file.header();
  PackPreamble preamble{kPackVersion,       static_cast<uint32_t>(table.size()),
                        file.fileBytes(),   original.sectionTableOffset,
                        original.headerCrc, static_cast<uint32_t>(kPackChunkBytes)};
  std::vector<uint8_t> pack(sizeof preamble + entries.size() * sizeof(PackEntry));
  std::memcpy(pack.data(), &preamble, sizeof preamble);
  std::memcpy(pack.data() + sizeof preamble, entries.data(), entries.size() * sizeof(PackEntry));
  std::vector<SectionEntry> packedTable;
  uint64_t at = sizeof(FileHeader);
  auto place = [&](uint32_t id, uint64_t bytes, const uint8_t* data) {
    at = alignUp(at, kSectionAlignment);
    packedTable.push_back(SectionEntry{id, 1, at, bytes, crc32c(data, bytes), 0});
    at += bytes;
  };
  for (size_t i = 0; i < table.size(); ++i)
    place(table[i].id, payloads[i].size(), payloads[i].data());
  place(static_cast<uint32_t>(SectionId::kPack), pack.size(), pack.data());
  const uint64_t tableOffset = alignUp(at, kSectionAlignment);
  FileHeader header = original;
  std::memcpy(header.magic, kPackedMagic, sizeof header.magic);
  header.sectionTableOffset = tableOffset;
  header.sectionCount = static_cast<uint32_t>(packedTable.size());
  header.headerCrc = headerChecksum(header);
  // Written piece by piece (no copy of the whole file): header, each payload after the zero
  // padding that aligns it, PACK, the table.
  static constexpr uint8_t kZeros[kSectionAlignment] = {};
  std::vector<std::span<const uint8_t>> pieces;
  uint64_t written = 0;
  auto append = [&](uint64_t offset, std::span<const uint8_t> bytes) {
    pieces.emplace_back(kZeros, offset - written);
    pieces.push_back(bytes);
    written = offset + bytes.size();
  };
  append(0, std::span(reinterpret_cast<const uint8_t*>(&header), sizeof header));
  for (size_t i = 0; i < table.size(); ++i) append(packedTable[i].offset, payloads[i]);
  append(packedTable.back().offset, pack);
  append(tableOffset, std::span(reinterpret_cast<const uint8_t*>(packedTable.data()),
                                packedTable.size() * sizeof(SectionEntry)));
  report.outputBytes = written;
  reportProgress(options.progress, 0.95, "writing");
  VOXLINK_RETURN_IF_ERROR(writeWholeFile(path, pieces));
  reportProgress(options.progress, 1.0, "packed");
  report.packSeconds = secondsSince(start);
  return report;
}

Result<VoxLinkFile> unpackFile(std::span<const uint8_t> packed, const std::string& name,
                               uint64_t maxBytes, unsigned threads,
                               const ProgressCallback& progress) {
  if (packed.size() < sizeof(FileHeader))
    return makeError(ErrorCode::kTruncated, name, ": header: packed file has ", packed.size(),
                     " bytes, a header needs ", sizeof(FileHeader));
  if (!isPackedFile(packed))
    return makeError(ErrorCode::kNotAVoxLinkFile, name,
                     ": header.magic: not a packed VoxLink file (expected \"VOXLINKZ\")");
  FileHeader header;
  std::memcpy(&header, packed.data(), sizeof header);
  if (kCheckPackedChecksums && headerChecksum(header) != header.headerCrc)
    return makeError(ErrorCode::kCorrupt, name, ": header.headerCrc: checksum mismatch");
  if (header.sectionCount == 0 || header.sectionCount > kMaxSectionCount ||
      header.sectionTableOffset > packed.size() ||
      uint64_t{header.sectionCount} * sizeof(SectionEntry) >
          packed.size() - header.sectionTableOffset)
    return makeError(ErrorCode::kTruncated, name, ": header.sectionTableOffset: table of ",
                     header.sectionCount, " entries lies beyond the end of the ", packed.size(),
                     "-byte file");
  std::vector<SectionEntry> table(header.sectionCount);
  std::memcpy(table.data(), packed.data() + header.sectionTableOffset,
              table.size() * sizeof(SectionEntry));
  const SectionEntry* packEntry = nullptr;
  for (size_t i = 0; i < table.size(); ++i) {
    const SectionEntry& e = table[i];
    // Named before anything else: a wiped table passed the checks below (empty payloads have
    // CRC 0) and was reported as "section PACK: missing".
    if (e.id == 0 && e.offset == 0 && e.bytes == 0 && e.crc == 0)
      return makeError(ErrorCode::kCorrupt, name, ": section table entry ", i, " (at byte ",
                       header.sectionTableOffset + i * sizeof(SectionEntry),
                       ") is all zeros: the section table is damaged");
    if (e.reserved != 0)
      return makeError(ErrorCode::kCorrupt, name, ": section ", nameOf(e.id),
                       ".reserved: ", e.reserved, " (must be 0)");
    if (e.offset > packed.size() || e.bytes > packed.size() - e.offset)
      return makeError(ErrorCode::kTruncated, name, ": section ", nameOf(e.id),
                       ": packed payload lies beyond the end of the file");
    if (kCheckPackedChecksums && crc32c(packed.data() + e.offset, e.bytes) != e.crc)
      return makeError(ErrorCode::kCorrupt, name, ": section ", nameOf(e.id),
                       ".crc: checksum mismatch in the packed payload");
    if (e.id == static_cast<uint32_t>(SectionId::kPack)) packEntry = &e;
  }
  if (!packEntry) return makeError(ErrorCode::kCorrupt, name, ": section PACK: missing");
  PackPreamble preamble;
  if (packEntry->bytes < sizeof preamble)
    return makeError(ErrorCode::kTruncated, name, ": section PACK: too short");
  std::memcpy(&preamble, packed.data() + packEntry->offset, sizeof preamble);
  if (preamble.version != kPackVersion)
    return makeError(ErrorCode::kUnsupported, name, ": section PACK.version: ", preamble.version,
                     " (this reader knows ", kPackVersion, ")");
  if (preamble.chunkBytes != kPackChunkBytes)
    return makeError(ErrorCode::kUnsupported, name,
                     ": section PACK.chunkBytes: ", preamble.chunkBytes, " (expected ",
                     kPackChunkBytes, ")");
  if (preamble.entryCount == 0 || preamble.entryCount > kMaxSectionCount ||
      packEntry->bytes != sizeof preamble + uint64_t{preamble.entryCount} * sizeof(PackEntry))
    return makeError(ErrorCode::kCorrupt, name, ": section PACK.entryCount: ", preamble.entryCount,
                     " does not match the section's ", packEntry->bytes, " bytes");
  if (preamble.originalFileBytes > maxBytes)
    return makeError(ErrorCode::kTooLarge, name,
                     ": section PACK.originalFileBytes: ", preamble.originalFileBytes,
                     " exceeds the limit of ", maxBytes, " bytes unpacked in memory");
  std::vector<PackEntry> entries(preamble.entryCount);
  std::memcpy(entries.data(), packed.data() + packEntry->offset + sizeof preamble,
              entries.size() * sizeof(PackEntry));

  // The original header, checked before anything is allocated for it.
  FileHeader original = header;
  std::memcpy(original.magic, kMagic, sizeof original.magic);
  original.sectionTableOffset = preamble.originalTableOffset;
  original.sectionCount = preamble.entryCount;
  original.headerCrc = preamble.originalHeaderCrc;
  // Before the checksum: a set reserved byte (with the packed header's CRC made right) was
  // reported as "the restored header does not match" its checksum.
  for (size_t i = 0; i < sizeof original.reserved; ++i)
    if (original.reserved[i] != 0)
      return makeError(ErrorCode::kCorrupt, name, ": header.reserved: byte ", i, " is not zero");
  if (kCheckPackedChecksums && headerChecksum(original) != original.headerCrc)
    return makeError(ErrorCode::kCorrupt, name,
                     ": section PACK.originalHeaderCrc: the restored header does not match it");
  // (The header is restored first: the file must hold it, and its table must lie after it.)
  if (preamble.originalFileBytes < sizeof(FileHeader))
    return makeError(ErrorCode::kCorrupt, name,
                     ": section PACK.originalFileBytes: ", preamble.originalFileBytes,
                     " bytes cannot hold the ", sizeof(FileHeader), "-byte header");
  if (preamble.originalTableOffset < sizeof(FileHeader))
    return makeError(ErrorCode::kCorrupt, name,
                     ": section PACK.originalTableOffset: ", preamble.originalTableOffset,
                     " lies inside the ", sizeof(FileHeader), "-byte header");
  VOXLINK_RETURN_IF_ERROR(checkHeader(original, preamble.originalFileBytes, name));
  // Zeroed by calloc: a large block comes zeroed from the system, so the decoding threads are
  // the first to touch its pages (a zero-filled vector is written over once by this thread).
  const std::shared_ptr<uint8_t> buffer(
      static_cast<uint8_t*>(std::calloc(preamble.originalFileBytes, 1)), FreeDeleter());
  if (!buffer)
    return makeError(ErrorCode::kTooLarge, name, ": section PACK.originalFileBytes: no memory for ",
                     preamble.originalFileBytes, " bytes");
  const std::span<uint8_t> bytes(buffer.get(), preamble.originalFileBytes);
  std::memcpy(bytes.data(), &original, sizeof original);
  std::vector<SectionEntry> originalTable(entries.size());
  for (size_t i = 0; i < entries.size(); ++i) originalTable[i] = entries[i].original;
  const uint64_t tableBegin = original.sectionTableOffset;
  const uint64_t tableEnd = tableBegin + originalTable.size() * sizeof(SectionEntry);
  std::memcpy(bytes.data() + tableBegin, originalTable.data(), tableEnd - tableBegin);

  // Sections share 90 % of the bar by their bytes; checking the checksums is the rest.
  uint64_t totalBytes = 0, doneBytes = 0;
  for (const PackEntry& p : entries) totalBytes += p.original.bytes;
  auto decoded = [&](uint64_t sectionBytes) {
    doneBytes += sectionBytes;
    reportProgress(progress, 0.9 * double(doneBytes) / double(std::max<uint64_t>(1, totalBytes)),
                   "unpacking");
  };
  reportProgress(progress, 0, "unpacking");
  const PackEntry* residual = nullptr;
  std::span<const uint8_t> residualPayload;
  std::vector<const PackEntry*> derived;
  const SectionEntry* masks = nullptr;
  for (const PackEntry& p : entries) {
    const SectionEntry& e = p.original;
    const std::string where = name + ": section " + nameOf(e.id);
    if (e.offset < sizeof(FileHeader) || e.offset > bytes.size() ||
        e.bytes > bytes.size() - e.offset)
      return makeError(ErrorCode::kCorrupt, where, ": original bytes [", e.offset, ", ",
                       e.offset + e.bytes, ") lie outside the ", bytes.size(), "-byte file");
    // Decoding must not write over the table restored above: the file would then be read
    // through a table the packed file chose, and GRAD filled in by the wrong bounds.
    if (e.bytes > 0 && e.offset < tableEnd && tableBegin < e.offset + e.bytes)
      return makeError(ErrorCode::kCorrupt, where, ": original bytes [", e.offset, ", ",
                       e.offset + e.bytes, ") overlap the section table [", tableBegin, ", ",
                       tableEnd, ")");
    if (p.reserved != 0)
      return makeError(ErrorCode::kCorrupt, name, ": section PACK: entry of ", nameOf(e.id),
                       ": reserved word ", p.reserved, " (must be 0)");
    if (!isKnownSectionCodec(p.codec))
      return makeError(ErrorCode::kUnsupported, where, ": codec ", p.codec, " is not known");
    const SectionEntry* source = nullptr;
    for (const SectionEntry& t : table)
      if (t.id == e.id) source = &t;
    if (!source || e.id == static_cast<uint32_t>(SectionId::kPack))
      return makeError(ErrorCode::kCorrupt, where, ": no packed payload");
    const auto payload = packed.subspan(source->offset, source->bytes);
    const auto codec = static_cast<SectionCodec>(p.codec);
    if (isGradientResidual(codec)) {
      if (e.id != static_cast<uint32_t>(SectionId::kGradients) || residual)
        return makeError(ErrorCode::kCorrupt, where, ": codec ", p.codec,
                         " (gradient residual) is only for GRAD");
      residual = &p;
      residualPayload = payload;
      continue;  // needs the other sections first
    }
    if (codec == SectionCodec::kDerived) {
      if ((e.id != static_cast<uint32_t>(SectionId::kRowStart) &&
           e.id != static_cast<uint32_t>(SectionId::kBrickVoxelBase)) ||
          !payload.empty())
        return makeError(ErrorCode::kCorrupt, where,
                         ": codec 5 (derived, no payload) is only "
                         "for ROWS and BVOX");
      derived.push_back(&p);
      continue;  // needs MASK first
    }
    if (e.id == static_cast<uint32_t>(SectionId::kRowMask)) masks = &e;
    VOXLINK_RETURN_IF_ERROR(decodeSection(payload, e.elementBytes, codec,
                                          bytes.subspan(e.offset, e.bytes), where, threads));
    decoded(e.bytes);
  }
  for (const PackEntry* p : derived) {
    const SectionEntry& e = p->original;
    const std::string where = name + ": section " + nameOf(e.id);
    if (!masks) return makeError(ErrorCode::kCorrupt, where, ": derived, but there is no MASK");
    VOXLINK_RETURN_IF_ERROR(derive(static_cast<SectionId>(e.id),
                                   bytes.subspan(masks->offset, masks->bytes), original.brickSize,
                                   bytes.subspan(e.offset, e.bytes), where, threads));
    decoded(e.bytes);
  }
  VOXLINK_ASSIGN_OR_RETURN(
      VoxLinkFile file, VoxLinkFile::parseOwned(std::shared_ptr<const void>(buffer, buffer.get()),
                                                bytes.data(), bytes.size(), name, packed.size()));
  if (residual) {
    // The prediction reads the structure and the values: check those first.
    VOXLINK_RETURN_IF_ERROR(validateStructure(file));
    const SectionEntry& e = residual->original;
    const auto codec = static_cast<SectionCodec>(residual->codec);
    // GRAD is filled in here, in the buffer the file was parsed from, before anyone else sees
    // the file. Its bounds are the ones checked above (the table, which cannot have been
    // written over, names the same).
    const std::span<uint8_t> grad = bytes.subspan(e.offset, e.bytes);
    VOXLINK_RETURN_IF_ERROR(decodeSection(residualPayload, e.elementBytes, codec, grad,
                                          name + ": section GRAD", threads));
    const uint64_t count = sampleSlots(file.header());
    if (count * 2 > grad.size())
      return makeError(ErrorCode::kCorrupt, name, ": section GRAD: ", grad.size(), " bytes for ",
                       count, " gradients");
    // The residuals become the codes in place (GRAD's offset is a multiple of 64, checked when
    // the file was parsed).
    addPredictedGradientCodes(file, std::span(reinterpret_cast<uint16_t*>(grad.data()), count),
                              predictionOf(codec), threads);
    decoded(e.bytes);
  }
  // Every section must be what was packed.
  const auto& sections = file.sectionTable();
  const std::vector<uint32_t> crcs = sectionChecksums(file, threads);
  for (size_t i = 0; i < sections.size(); ++i)
    if (crcs[i] != sections[i].crc)
      return makeError(ErrorCode::kCorrupt, name, ": section ", nameOf(sections[i].id),
                       ": unpacked bytes do not match the original checksum");
  reportProgress(progress, 1.0, "unpacked");
  return file;
}

}  // namespace voxlink::pack
