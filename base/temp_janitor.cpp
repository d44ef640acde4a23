// SPDX-License-Identifier: BSD-3-Clause
#include "base/temp_janitor.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <set>

namespace voxlink {
inline namespace base {
namespace {

int janitorSocket = -1;

[[noreturn]] void runJanitor(int socket) {
  setsid();  // out of the rank's process group: a signal to the group must not end it too
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) signal(sig, SIG_IGN);
  const int null = ::open("/dev/null", O_RDWR);
  for (int fd : {0, 1, 2}) dup2(null, fd);  // nor keep the launcher's output pipes open
  std::set<std::string> live;
  std::string pending;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(socket, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    pending.append(buffer, static_cast<size_t>(n));
    for (size_t end; (end = pending.find('\n')) != std::string::npos; pending.erase(0, end + 1)) {
      if (end == 0) continue;
      const std::string path = pending.substr(1, end - 1);
      if (pending[0] == '+')
        live.insert(path);
      else
        live.erase(path);
    }
  }
  for (const std::string& path : live) ::unlink(path.c_str());
  _exit(0);
}

}  // namespace

bool startTempJanitor() {
  int fds[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0) return false;
  const pid_t pid = fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return false;
  }
  if (pid == 0) {
    ::close(fds[0]);
    runJanitor(fds[1]);
  }
  ::close(fds[1]);
  janitorSocket = fds[0];
  return true;
}

void tellTempJanitor(char op, const std::string& path) {
  if (janitorSocket < 0) return;
  const std::string line = op + path + '\n';
  // MSG_NOSIGNAL: a helper that is gone must not end this process with SIGPIPE.
  for (size_t sent = 0; sent < line.size();) {
    const ssize_t n = ::send(janitorSocket, line.data() + sent, line.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    sent += static_cast<size_t>(n);
  }
}

}  // namespace base
}  // namespace voxlink
