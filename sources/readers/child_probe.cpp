// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/child_probe.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

// Set by a sanitizer runtime when there is one (weak: null otherwise). libFuzzer registers a
// callback here that saves the current input as a crash when the sanitizer ends the process.
extern "C" void __sanitizer_set_death_callback(void (*callback)(void)) __attribute__((weak));

namespace voxlink::sources {

namespace {

constexpr uint32_t kThrownMarker = 0xFFFFFFFFu;  // followed by the message, up to EOF
constexpr std::chrono::seconds kChildTimeLimit{300};

void writeAll(int fd, const void* data, size_t bytes) {
  const auto* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t n = write(fd, p, bytes);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) _exit(0);  // the parent is gone
    p += n;
    bytes -= static_cast<size_t>(n);
  }
}

// The child's address space now plus `bytes`, as its RLIMIT_AS (no limit if /proc is missing).
void limitAddressSpace(uint64_t bytes) {
  std::FILE* statm = std::fopen("/proc/self/statm", "r");
  if (!statm) return;
  unsigned long long pages = 0;
  const bool read = std::fscanf(statm, "%llu", &pages) == 1;
  std::fclose(statm);
  if (!read) return;
  const uint64_t now = pages * static_cast<uint64_t>(sysconf(_SC_PAGESIZE));
  const rlimit limit{now + bytes, now + bytes};
  setrlimit(RLIMIT_AS, &limit);
}

}  // namespace

ProbeOutcome probeInChild(const std::function<void(const MarkFn& mark)>& work,
                          uint64_t memoryBytes) {
  ProbeOutcome outcome;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) return outcome;  // not leaked into programs run meanwhile
  const pid_t child = fork();
  if (child < 0) {
    close(fds[0]);
    close(fds[1]);
    return outcome;
  }
  if (child == 0) {
    close(fds[0]);
    // The parent's crash handlers (a crash reporter, libFuzzer, a sanitizer) would turn a crash
    // into an ordinary exit, which reads as "survived": the child must die by the signal.
    for (const int crash : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGTRAP, SIGSYS})
      signal(crash, SIG_DFL);
    // Likewise a sanitizer's death callback: under libFuzzer, a child that the memory bound
    // stops (the sanitizer reports out-of-memory and exits) would be saved as a crash of the
    // parent although the parent handles it.
    if (&__sanitizer_set_death_callback != nullptr) __sanitizer_set_death_callback(nullptr);
    const int devNull = open("/dev/null", O_WRONLY);
    if (devNull >= 0) dup2(devNull, STDERR_FILENO);  // the library's and assert's messages
    if (memoryBytes > 0) limitAddressSpace(memoryBytes);
    const int out = fds[1];
    const MarkFn mark = [out](uint32_t i) { writeAll(out, &i, sizeof i); };
    std::string thrown;
    try {
      work(mark);
      _exit(0);
    } catch (const std::exception& e) {
      thrown = e.what();
    } catch (...) {
      thrown = "unknown exception";
    }
    writeAll(out, &kThrownMarker, sizeof kThrownMarker);
    writeAll(out, thrown.data(), thrown.size());
    _exit(0);
  }
  close(fds[1]);
  // Everything the child wrote: marks, then maybe the exception marker and its message. A child
  // that neither finishes nor dies in time (forked from a process whose other threads held a
  // lock the child then needs) is killed, and the caller reads unguarded.
  std::string received;
  char buffer[4096];
  const auto deadline = std::chrono::steady_clock::now() + kChildTimeLimit;
  bool timedOut = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    pollfd p{fds[0], POLLIN, 0};
    const int ready = left.count() > 0 ? poll(&p, 1, static_cast<int>(left.count())) : 0;
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) {
      timedOut = true;
      break;
    }
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n > 0) {
      received.append(buffer, static_cast<size_t>(n));
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    break;
  }
  close(fds[0]);
  if (timedOut) {
    kill(child, SIGKILL);
    while (waitpid(child, nullptr, 0) < 0 && errno == EINTR) {
    }
    return ProbeOutcome{};
  }
  for (size_t at = 0; at + sizeof(uint32_t) <= received.size(); at += sizeof(uint32_t)) {
    uint32_t index;
    std::memcpy(&index, received.data() + at, sizeof index);
    if (index == kThrownMarker) {
      outcome.thrown = received.substr(at + sizeof index);
      break;
    }
    outcome.lastMark = index;
  }
  int status = 0;
  while (waitpid(child, &status, 0) < 0) {
    if (errno != EINTR) return outcome;
  }
  if (WIFSIGNALED(status)) {
    outcome.died = true;
    outcome.signal = WTERMSIG(status);
  } else if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
    outcome.died = true;
    outcome.exitStatus = WEXITSTATUS(status);
  }
  return outcome;
}

std::string describeDeath(const ProbeOutcome& outcome) {
  if (outcome.signal != 0) return strsignal(outcome.signal);
  return "exit status " + std::to_string(outcome.exitStatus);
}

}  // namespace voxlink::sources
