#include "sources/readers/gdcm_guard.h"

#include <gdcmImageReader.h>
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
