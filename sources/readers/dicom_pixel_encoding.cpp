// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/dicom_pixel_encoding.h"

#include <gdcmTransferSyntax.h>

#include <algorithm>
#include <cstring>

#include "sources/readers/detail/dicom_tags.h"

namespace voxlink::sources {
namespace {

// The standard's names of the image syntaxes (GDCM's own strings are the UIDs).
struct SyntaxName {
  const char* uid;
  const char* name;
};
constexpr SyntaxName kSyntaxNames[] = {
    {"1.2.840.10008.1.2", "Implicit VR Little Endian"},
    {"1.2.840.10008.1.2.1", "Explicit VR Little Endian"},
    {"1.2.840.10008.1.2.1.99", "Deflated Explicit VR Little Endian"},
    {"1.2.840.10008.1.2.2", "Explicit VR Big Endian"},
    {"1.2.840.10008.1.2.4.50", "JPEG Baseline"},
    {"1.2.840.10008.1.2.4.51", "JPEG Extended"},
    {"1.2.840.10008.1.2.4.57", "JPEG Lossless"},
    {"1.2.840.10008.1.2.4.70", "JPEG Lossless SV1"},
    {"1.2.840.10008.1.2.4.80", "JPEG-LS Lossless"},
    {"1.2.840.10008.1.2.4.81", "JPEG-LS Near-Lossless"},
    {"1.2.840.10008.1.2.4.90", "JPEG 2000 Lossless"},
    {"1.2.840.10008.1.2.4.91", "JPEG 2000"},
    {"1.2.840.10008.1.2.5", "RLE Lossless"},
    // Unknown to GDCM 3.0:
    {"1.2.840.10008.1.2.4.201", "High-Throughput JPEG 2000 (Lossless Only)"},
    {"1.2.840.10008.1.2.4.202", "High-Throughput JPEG 2000 with RPCL Options (Lossless Only)"},
    {"1.2.840.10008.1.2.4.203", "High-Throughput JPEG 2000"},
    {"1.2.840.10008.1.2.4.110", "JPEG XL Lossless"},
    {"1.2.840.10008.1.2.4.111", "JPEG XL JPEG Recompression"},
    {"1.2.840.10008.1.2.4.112", "JPEG XL"},
    {"1.2.840.10008.1.2.4.94", "JPIP Referenced"},
    {"1.2.840.10008.1.2.4.95", "JPIP Referenced Deflate"},
    {"1.2.840.10008.1.2.4.96", "JPIP HTJ2K Referenced"},
    {"1.2.840.10008.1.2.4.97", "JPIP HTJ2K Referenced Deflate"},
};

gdcm::TransferSyntax::TSType syntaxType(const std::string& uid) {
  return gdcm::TransferSyntax::GetTSType(uid.c_str());
}

// Native and compressed image syntaxes GDCM decodes; video (MPEG, H.264) and references (JPIP)
// have no pixels GDCM can give.
bool gdcmDecodes(const std::string& uid) {
  using TS = gdcm::TransferSyntax;
  switch (syntaxType(uid)) {
    case TS::MPEG2MainProfile:
    case TS::MPEG2MainProfileHighLevel:
    case TS::MPEG4AVCH264HighProfileLevel4_1:
    case TS::MPEG4AVCH264BDcompatibleHighProfileLevel4_1:
    case TS::JPIPReferenced:
    case TS::TS_END:
      return false;
    default:
      return true;
  }
}

template <class T>
void extendSignOf(T* v, uint64_t count, int bitsStored) {
  using U = std::make_unsigned_t<T>;
  const U mask = static_cast<U>((U{1} << bitsStored) - 1);
  const U sign = static_cast<U>(U{1} << (bitsStored - 1));
  for (uint64_t i = 0; i < count; ++i) {
    const U low = static_cast<U>(static_cast<U>(v[i]) & mask);
    // (low ^ sign) - sign: the two's complement value of the low bits, without overflow.
    v[i] = static_cast<T>(static_cast<int64_t>(low ^ sign) - static_cast<int64_t>(sign));
  }
}

}  // namespace

std::string transferSyntaxUid(const gdcm::FileMetaInformation& meta) {
  return stringValue(meta, 0x0002, 0x0010);
}

std::string transferSyntaxName(const std::string& uid) {
  for (const SyntaxName& s : kSyntaxNames)
    if (uid == s.uid) return cat(s.name, " (", uid, ")");
  return cat(syntaxType(uid) == gdcm::TransferSyntax::TS_END ? "unknown syntax " : "syntax ", uid);
}

bool isDeflatedSyntax(const std::string& uid) {
  return syntaxType(uid) == gdcm::TransferSyntax::DeflatedExplicitVRLittleEndian;
}

bool isBigEndianSyntax(const std::string& uid) {
  return syntaxType(uid) == gdcm::TransferSyntax::ExplicitVRBigEndian;
}

bool isEncapsulatedSyntax(const std::string& uid) {
  const auto type = syntaxType(uid);
  return type != gdcm::TransferSyntax::TS_END && gdcm::TransferSyntax(type).IsEncapsulated();
}

Status checkPixelEncoding(const gdcm::DataSet& ds, const std::string& syntaxUid,
                          const std::string& file) {
  if (!syntaxUid.empty() && !gdcmDecodes(syntaxUid))
    return makeError(ErrorCode::kUnsupported, file,
                     ": tag TransferSyntaxUID (0002,0010): ", transferSyntaxName(syntaxUid),
                     " is not supported (GDCM ",
                     "cannot decode it; convert the file to an uncompressed syntax first)");
  const int samples = ushortValue<0x0028, 0x0002>(ds).value_or(1);
  if (samples != 1)
    return makeError(ErrorCode::kUnsupported, file, ": tag SamplesPerPixel (0028,0002): ", samples,
                     " (", stringValue(ds, 0x0028, 0x0004), " color; only single-channel images)");
  const auto allocated = ushortValue<0x0028, 0x0100>(ds);
  if (!allocated) return Status::ok();  // no image: the header reader says so
  if (*allocated != 8 && *allocated != 16 && *allocated != 32)
    return makeError(ErrorCode::kUnsupported, file, ": tag BitsAllocated (0028,0100): ", *allocated,
                     *allocated == 1 ? " (a 1-bit bitmap such as a segmentation; " : " (",
                     "8, 16 or 32 are supported)");
  const int stored = ushortValue<0x0028, 0x0101>(ds).value_or(*allocated);
  if (stored < 1 || stored > *allocated)
    return makeError(ErrorCode::kCorrupt, file, ": tag BitsStored (0028,0101): ", stored,
                     ", expected 1..", *allocated, " (BitsAllocated)");
  const int high = ushortValue<0x0028, 0x0102>(ds).value_or(stored - 1);
  if (high != stored - 1)
    return makeError(ErrorCode::kUnsupported, file, ": tag HighBit (0028,0102): ", high,
                     " with BitsStored ", stored, " (only pixels in the low bits, HighBit ",
                     stored - 1, ")");
  return Status::ok();
}

void extendSign(void* values, ScalarType type, uint64_t count, int bitsStored) {
  switch (type) {
    case ScalarType::kI8:
      if (bitsStored < 8) extendSignOf(static_cast<int8_t*>(values), count, bitsStored);
      break;
    case ScalarType::kI16:
      if (bitsStored < 16) extendSignOf(static_cast<int16_t*>(values), count, bitsStored);
      break;
    case ScalarType::kI32:
      if (bitsStored < 32) extendSignOf(static_cast<int32_t*>(values), count, bitsStored);
      break;
    default:
      break;
  }
}

void swapEachValue(void* values, size_t elementBytes, uint64_t count) {
  auto* p = static_cast<uint8_t*>(values);
  for (uint64_t i = 0; i < count; ++i, p += elementBytes) std::reverse(p, p + elementBytes);
}

}  // namespace voxlink::sources
