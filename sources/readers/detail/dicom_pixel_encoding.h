// SPDX-License-Identifier: BSD-3-Clause
// How a DICOM file's pixels are encoded, decided from its header before any pixel is decoded
// (GDCM aborts the process on some encodings, and spends seconds and gigabytes on others before
// failing), and the corrections the reader applies to what GDCM decodes.
#pragma once

#include <gdcmDataSet.h>
#include <gdcmFileMetaInformation.h>

#include <cstdint>
#include <string>

#include "base/error.h"
#include "format/scalar_type.h"

namespace voxlink::sources {

// TransferSyntaxUID (0002,0010) of the file meta information; empty when absent (ACR-NEMA).
std::string transferSyntaxUid(const gdcm::FileMetaInformation& meta);

// "Explicit VR Big Endian (1.2.840.10008.1.2.2)": the syntax's name and UID, for messages.
std::string transferSyntaxName(const std::string& uid);

bool isDeflatedSyntax(const std::string& uid);   // 1.2.840.10008.1.2.1.99
bool isBigEndianSyntax(const std::string& uid);  // 1.2.840.10008.1.2.2
bool isEncapsulatedSyntax(const std::string& uid);

// kUnsupported when the reader cannot give the pixel values: a transfer syntax GDCM does not
// decode (HTJ2K, JPEG XL, MPEG, ...), SamplesPerPixel other than 1 (color), BitsAllocated other
// than 8, 16, 32 (1-bit segmentations), HighBit not BitsStored - 1. kCorrupt for BitsStored 0 or
// above BitsAllocated. Reads header elements only; messages name the file and the tag.
Status checkPixelEncoding(const gdcm::DataSet& ds, const std::string& syntaxUid,
                          const std::string& file);

// Signed values (PixelRepresentation 1) from their low `bitsStored` bits, as DICOM defines
// them: JPEG-LS has no signed samples and JPEG 2000 codestreams may say unsigned, so GDCM returns
// the bit pattern (-2073 in 15 bits as 30695). Values of `type` (i8, i16, i32), in place.
void extendSign(void* values, ScalarType type, uint64_t count, int bitsStored);

// Reverses the bytes of each `elementBytes`-byte value (big-endian pixels), in place.
void swapEachValue(void* values, size_t elementBytes, uint64_t count);

}  // namespace voxlink::sources
