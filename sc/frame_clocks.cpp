// Clocks per frame in a child process (sc/frame_clocks.hpp).
#include "sc/frame_clocks.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include "sc/cycle_model.hpp"

namespace fxr::cyc {

namespace {
// The child's answer on the pipe: ok flag, clocks, and an error text when not ok.
struct Answer {
  uint8_t ok = 0;
  uint64_t clocks = 0;
  char what[256] = {};
};

bool write_all(int fd, const void* p, size_t n) {
  const char* c = static_cast<const char*>(p);
  while (n > 0) {
    const ssize_t w = ::write(fd, c, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    c += w, n -= (size_t)w;
  }
  return true;
}
}  // namespace

uint64_t unit_frame_clocks(const Config& cfg, const ArchConfig& arch, const DrawState& st,
                           const std::vector<ClipTriangle>& prims) {
  int fd[2];
  if (::pipe(fd) != 0) throw std::runtime_error(std::string("unit_frame_clocks: pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fd[0]), ::close(fd[1]);
    throw std::runtime_error(std::string("unit_frame_clocks: fork: ") + std::strerror(errno));
  }
  if (pid == 0) {  // the child: one simulation, the answer, and out without running destructors
    ::close(fd[0]);
    Answer a;
    try {
      FrameOutput f;
      a.clocks = run_unit_cycles(cfg, arch, st, prims, f, nullptr).clocks;
      a.ok = 1;
    } catch (const std::exception& e) {
      std::strncpy(a.what, e.what(), sizeof a.what - 1);
    }
    ::_exit(write_all(fd[1], &a, sizeof a) ? 0 : 1);
  }
  ::close(fd[1]);
  Answer a;
  size_t got = 0;
  while (got < sizeof a) {
    const ssize_t r = ::read(fd[0], reinterpret_cast<char*>(&a) + got, sizeof a - got);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) break;
    got += (size_t)r;
  }
  ::close(fd[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (got != sizeof a || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("unit_frame_clocks: the cycle model's child process failed (status " + std::to_string(status) + ")");
  if (!a.ok) throw std::runtime_error(std::string("unit_frame_clocks: ") + a.what);
  return a.clocks;
}

}  // namespace fxr::cyc
