// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/gdcm_guard.h"

#include <gdcmAttribute.h>
#include <gdcmBoxRegion.h>
#include <gdcmImageRegionReader.h>
#include <gdcmPixmapReader.h>
#include <gdcmReader.h>
#include <gdcmTrace.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

#include "base/limits.h"
#include "sources/readers/detail/child_probe.h"
#include "sources/readers/detail/dicom_pixel_encoding.h"
#include "sources/readers/detail/dicom_tags.h"

namespace voxlink::sources {
namespace {

bool multiFrame(const gdcm::DataSet& ds) {
  gdcm::Attribute<0x0028, 0x0008> frames;
  if (!ds.FindDataElement(frames.GetTag()) || ds.GetDataElement(frames.GetTag()).IsEmpty())
    return false;
  frames.SetFromDataSet(ds);
  return frames.GetValue() > 1;
}

// A multi-frame file as the reader decodes it: one frame at a time (memory of one frame, not
// of the whole volume).
void readFrameByFrame(const std::string& file) {
  gdcm::ImageRegionReader reader;
  reader.SetFileName(file.c_str());
  if (!reader.ReadInformation()) return;
  const unsigned int* dims = reader.GetImage().GetDimensions();
  if (!dims || dims[0] == 0 || dims[1] == 0) return;
  for (unsigned int z = 0; z < dims[2]; ++z) {
    gdcm::BoxRegion box;
    box.SetDomain(0, dims[0] - 1, 0, dims[1] - 1, z, z);
    reader.SetRegion(box);
    const size_t bytes = reader.ComputeBufferLength();
    if (bytes == 0 || bytes > (size_t{1} << 31)) return;
    std::vector<char> buffer(bytes);
    if (!reader.ReadIntoBuffer(buffer.data(), bytes)) return;
  }
}

// The whole image as the reader decodes a single frame or a deflated file, unless the header
// says the reader will refuse it (then it is never decoded: GDCM aborts on some such files).
void readWhole(const std::string& file, const std::string& syntax) {
  gdcm::PixmapReader reader;
  reader.SetFileName(file.c_str());
  if (!reader.Read()) return;
  if (!checkPixelEncoding(reader.GetFile().GetDataSet(), syntax, file)) return;
  const gdcm::Pixmap& image = reader.GetPixmap();
  const unsigned long bytes = image.GetBufferLength();
  if (bytes == 0 || bytes > (1ul << 31)) return;
  std::vector<char> buffer(bytes);
  image.GetBuffer(buffer.data());
}

// What a file is, from the header GDCM read before it died decoding the pixels, for the error.
std::string describeImage(const std::string& file) {
  gdcm::Reader header;
  header.SetFileName(file.c_str());
  const gdcm::Tag pixelData(0x7fe0, 0x0010);
  if (!header.ReadUpToTag(pixelData, {pixelData})) return "";
  const gdcm::DataSet& ds = header.GetFile().GetDataSet();
  const std::string frames = stringValue(ds, 0x0028, 0x0008);
  return cat(": a ", stringValue(ds, 0x0008, 0x0060), " image in ",
             transferSyntaxName(transferSyntaxUid(header.GetFile().GetHeader())), ", ",
             ushortValue<0x0028, 0x0011>(ds).value_or(0), "x",
             ushortValue<0x0028, 0x0010>(ds).value_or(0), ", BitsAllocated ",
             ushortValue<0x0028, 0x0100>(ds).value_or(0), ", NumberOfFrames ",
             frames.empty() ? "absent" : frames);
}

}  // namespace

Status checkGdcmSurvives(const std::vector<std::string>& files) {
  // The child reads each file as the reader will: the header up to the pixel data, then the
  // whole image and its decoded buffer (GDCM's copy and ours: twice the largest file, plus the
  // fixed allowance). A damaged 19 KB file made GDCM allocate about 4 GB before giving up.
  // Marks: 2i while reading file i's header, 2i + 1 while decoding its pixels.
  uint64_t largest = 0;
  for (const std::string& f : files) {
    std::error_code ec;
    const uintmax_t size = std::filesystem::file_size(f, ec);
    if (!ec) largest = std::max<uint64_t>(largest, size);
  }
  const uint64_t memory = limits::kMaxGdcmProbeBytes + 2 * largest;
  const ProbeOutcome outcome = probeInChild(
      [&](const MarkFn& mark) {
        gdcm::Trace::WarningOff();
        gdcm::Trace::ErrorOff();
        gdcm::Trace::DebugOff();
        for (uint32_t i = 0; i < files.size(); ++i) {
          mark(2 * i);
          gdcm::Reader header;
          header.SetFileName(files[i].c_str());
          const gdcm::Tag pixelData(0x7fe0, 0x0010);
          const bool parsed = header.ReadUpToTag(pixelData, {pixelData});
          const std::string syntax = transferSyntaxUid(header.GetFile().GetHeader());
          const bool deflated = isDeflatedSyntax(syntax);
          if (!parsed && !deflated) continue;
          if (parsed && !checkPixelEncoding(header.GetFile().GetDataSet(), syntax, files[i]))
            continue;  // refused from the header by the reader, never decoded
          mark(2 * i + 1);
          if (parsed && !deflated && multiFrame(header.GetFile().GetDataSet()))
            readFrameByFrame(files[i]);
          else
            readWhole(files[i], syntax);
        }
      },
      memory);
  const uint32_t failed = outcome.lastMark ? *outcome.lastMark / 2 : 0;
  const bool decoding = outcome.lastMark && *outcome.lastMark % 2 == 1;
  if (outcome.died && outcome.lastMark && failed < files.size()) {
    if (decoding)
      return makeError(ErrorCode::kUnsupported, files[failed],
                       ": GDCM crashed decoding the pixel data (", describeDeath(outcome), ")",
                       describeImage(files[failed]), "; this encoding cannot be read");
    return makeError(ErrorCode::kCorrupt, files[failed], ": GDCM crashed reading this file (",
                     describeDeath(outcome), "); the file is damaged or not DICOM");
  }
  // GDCM ran out of its allowance: the in-process read would take as much again, so refuse.
  if (outcome.thrown && outcome.lastMark && failed < files.size())
    return makeError(ErrorCode::kCorrupt, files[failed], ": GDCM failed reading this ",
                     "file within ", memory >> 20, " MiB of memory (", *outcome.thrown,
                     "); the file is damaged or not DICOM");
  return Status::ok();
}

}  // namespace voxlink::sources
