#include "sources/readers/gdcm_guard.h"

#include <gdcmAttribute.h>
#include <gdcmBoxRegion.h>
#include <gdcmImageReader.h>
#include <gdcmImageRegionReader.h>
#include <gdcmReader.h>
#include <gdcmTrace.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

#include "format/limits.h"
#include "sources/readers/child_probe.h"

namespace voxlink::convert {
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

}  // namespace

Status checkGdcmSurvives(const std::vector<std::string>& files) {
  // The child reads each file as the reader will: the header up to the pixel data, then the
  // whole image and its decoded buffer (GDCM's copy and ours: twice the largest file, plus the
  // fixed allowance). A damaged 19 KB file made GDCM allocate about 4 GB before giving up.
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
          mark(i);
          gdcm::Reader header;
          header.SetFileName(files[i].c_str());
          const gdcm::Tag pixelData(0x7fe0, 0x0010);
          if (!header.ReadUpToTag(pixelData, {pixelData})) continue;
          if (multiFrame(header.GetFile().GetDataSet())) {
            readFrameByFrame(files[i]);
            continue;
          }
          gdcm::ImageReader reader;
          reader.SetFileName(files[i].c_str());
          if (!reader.Read()) continue;
          const gdcm::Image& image = reader.GetImage();
          const unsigned long bytes = image.GetBufferLength();
          if (bytes == 0 || bytes > (1ul << 31)) continue;
          std::vector<char> buffer(bytes);
          image.GetBuffer(buffer.data());
        }
      },
      memory);
  if (outcome.died && outcome.lastMark && *outcome.lastMark < files.size())
    return makeError(ErrorCode::kCorrupt, files[*outcome.lastMark],
                     ": GDCM crashed reading this file (", describeDeath(outcome),
                     "); the file is damaged or not DICOM");
  // GDCM ran out of its allowance: the in-process read would take as much again, so refuse.
  if (outcome.thrown && outcome.lastMark && *outcome.lastMark < files.size())
    return makeError(ErrorCode::kCorrupt, files[*outcome.lastMark], ": GDCM failed reading this ",
                     "file within ", memory >> 20, " MiB of memory (", *outcome.thrown,
                     "); the file is damaged or not DICOM");
  return Status::ok();
}

}  // namespace voxlink::convert
