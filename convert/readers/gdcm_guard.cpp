#include "convert/readers/gdcm_guard.h"

#include <fcntl.h>
#include <gdcmImageReader.h>
#include <gdcmReader.h>
#include <gdcmTrace.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <vector>

namespace voxlink::convert {
namespace {

// The child: reads each file as the reader will (header up to the pixel data, then the whole
// image and its decoded buffer), announcing each index first. Never returns.
[[noreturn]] void readAllInChild(const std::vector<std::string>& files, int out) {
  const int devNull = open("/dev/null", O_WRONLY);
  if (devNull >= 0) dup2(devNull, STDERR_FILENO);  // GDCM's and assert's messages
  gdcm::Trace::WarningOff();
  gdcm::Trace::ErrorOff();
  gdcm::Trace::DebugOff();
  for (uint32_t i = 0; i < files.size(); ++i) {
    if (write(out, &i, sizeof i) != sizeof i) _exit(0);  // the parent is gone
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
  _exit(0);
}

}  // namespace

Status checkGdcmSurvives(const std::vector<std::string>& files) {
  if (files.empty()) return Status::ok();
  int fds[2];
  if (pipe(fds) != 0) return Status::ok();  // cannot guard: read in-process as before
  const pid_t child = fork();
  if (child < 0) {
    close(fds[0]);
    close(fds[1]);
    return Status::ok();
  }
  if (child == 0) {
    close(fds[0]);
    readAllInChild(files, fds[1]);
  }
  close(fds[1]);
  uint32_t last = 0, index = 0;
  bool any = false;
  for (;;) {
    const ssize_t n = read(fds[0], &index, sizeof index);
    if (n == sizeof index) {
      last = index;
      any = true;
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    break;
  }
  close(fds[0]);
  int status = 0;
  while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status) && any && last < files.size())
    return makeError(ErrorCode::kCorrupt, files[last], ": GDCM crashed reading this file (",
                     strsignal(WTERMSIG(status)), "); the file is damaged or not DICOM");
  return Status::ok();
}

}  // namespace voxlink::convert
