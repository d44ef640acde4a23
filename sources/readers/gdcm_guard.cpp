#include "sources/readers/gdcm_guard.h"

#include <gdcmImageReader.h>
#include <gdcmReader.h>
#include <gdcmTrace.h>

#include <cstring>
#include <vector>

#include "sources/readers/child_probe.h"

namespace voxlink::convert {

Status checkGdcmSurvives(const std::vector<std::string>& files) {
  // The child reads each file as the reader will: the header up to the pixel data, then the
  // whole image and its decoded buffer.
  const ProbeOutcome outcome = probeInChild([&](const MarkFn& mark) {
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
  });
  if (outcome.died && outcome.lastMark && *outcome.lastMark < files.size())
    return makeError(ErrorCode::kCorrupt, files[*outcome.lastMark],
                     ": GDCM crashed reading this file (", describeDeath(outcome),
                     "); the file is damaged or not DICOM");
  return Status::ok();
}

}  // namespace voxlink::convert
