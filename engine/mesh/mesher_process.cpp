#include "engine/mesh/mesher_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "engine/common/errors.hpp"
#include "engine/mesh/mesh_bytes.hpp"
#include "engine/scene/mesh_budget.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define ROCKDD_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ROCKDD_ADDRESS_SANITIZER 1
#endif
#endif

namespace rockdd {

namespace {

/// What a meshing process hands back: its first byte says which.
enum Reply : char {
  kMesh = 'M',         // then the mesh (write_mesh)
  kInputError = 'I',   // then where, key and expected
  kOutOfMemory = 'B',  // std::bad_alloc: the address-space limit
  kOtherError = 'X',   // then the exception's text
};

/// A positive number from the environment variable `name`, or nullopt.
std::optional<double> positive_environment(const char* name) {
  const char* text = std::getenv(name);
  if (text == nullptr || *text == '\0') return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (*end != '\0' || !(value > 0))
    throw InputError(
        name, "",
        "expected a positive number (the environment variable), got \"" + std::string(text) + "\"");
  return value;
}

/// This process's address space (VmSize), bytes: the child starts with all of it.
[[maybe_unused]] double address_space_bytes() {
  std::ifstream statm("/proc/self/statm");
  double pages = 0.0;
  statm >> pages;
  return pages * static_cast<double>(sysconf(_SC_PAGESIZE));
}

std::string megabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f MB", bytes / 1e6);
  return text;
}

void write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // the parent went away: nobody to tell
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

/// The child: limits itself, makes the mesh, writes its reply and ends without running the
/// parent's exit handlers (Gmsh's and the test framework's belong to the parent).
[[noreturn]] void run_child(const std::function<Mesh()>& make, const MeshingLimits& limits, int fd,
                            pid_t parent) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // no orphan meshing on after the asker is gone
  if (::getppid() != parent) ::_exit(1);
  // A crash in Gmsh ends the child by its signal, which the parent reports as such. Handlers
  // inherited from the asking process (a sanitizer's, a fuzzer's) would report the child's
  // crash as that process's own: a fuzzer once recorded Gmsh's parser dividing by zero on a
  // malformed .geo as a finding of its own.
  for (const int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(signal, SIG_DFL);
  const rlimit no_core{0, 0};  // a crash of a process of gigabytes leaves no core file
  ::setrlimit(RLIMIT_CORE, &no_core);
#ifndef ROCKDD_ADDRESS_SANITIZER
  if (limits.bytes > 0) {
    const auto total = static_cast<rlim_t>(address_space_bytes() + limits.bytes);
    const rlimit space{total, total};
    ::setrlimit(RLIMIT_AS, &space);
  }
#endif
  ByteWriter out;
  try {
    const Mesh mesh = make();
    out.value(kMesh);
    write_mesh(out, mesh);
  } catch (const InputError& error) {
    out = ByteWriter();
    out.value(kInputError);
    out.text(error.where());
    out.text(error.key());
    out.text(error.expected());
  } catch (const std::bad_alloc&) {
    out = ByteWriter();
    out.value(kOutOfMemory);
  } catch (const std::exception& error) {
    out = ByteWriter();
    out.value(kOtherError);
    out.text(error.what());
  }
  write_all(fd, out.bytes());
  ::_exit(0);
}

/// Kills and reaps the child unless it was reaped, so that no exit path leaves it running.
class Child {
 public:
  explicit Child(pid_t pid) : pid_(pid) {}
  ~Child() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    wait();
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  /// Waits for the child to end; its status and peak RSS (bytes).
  int wait() {
    int status = 0;
    rusage usage{};
    while (::wait4(pid_, &status, 0, &usage) < 0 && errno == EINTR) {
    }
    pid_ = 0;
    peak_bytes_ = static_cast<double>(usage.ru_maxrss) * 1024.0;
    return status;
  }
  void kill() { ::kill(pid_, SIGKILL); }
  double peak_bytes() const { return peak_bytes_; }

 private:
  pid_t pid_;
  double peak_bytes_ = 0.0;
};

/// Resident memory of process `pid` (`self` for this one), bytes; 0 when it cannot be read.
double resident_bytes(const std::string& pid) {
  std::ifstream statm("/proc/" + pid + "/statm");
  double size = 0.0, resident = 0.0;
  statm >> size >> resident;
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

/// How reading a child's reply ended.
enum class ReplyEnd { complete, late, large };

/// Reads everything the child `pid` writes until it closes the pipe, unless `deadline` passes
/// first (late) or, looked at every 0.1 s, its resident memory exceeds `most_resident` bytes
/// (large: the limit that holds where RLIMIT_AS cannot, under AddressSanitizer).
ReplyEnd read_reply(int fd, pid_t pid, std::chrono::steady_clock::time_point deadline,
                    double most_resident, std::string& reply) {
  const std::string process = std::to_string(pid);
  char buffer[1 << 16];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return ReplyEnd::late;
    if (most_resident > 0 && resident_bytes(process) > most_resident) return ReplyEnd::large;
    pollfd wanted{fd, POLLIN, 0};
    const int ready = ::poll(&wanted, 1, static_cast<int>(std::min<long long>(left.count(), 100)));
    if (ready < 0 && errno != EINTR)
      throw std::runtime_error(std::string("poll: ") + strerror(errno));
    if (ready <= 0) continue;
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return ReplyEnd::complete;  // closed: the child wrote all, or died
    reply.append(buffer, static_cast<std::size_t>(n));
  }
}

class Pipe {
 public:
  Pipe() {
    if (::pipe2(fds_, O_CLOEXEC) != 0)
      throw std::runtime_error(std::string("meshing process: pipe: ") + strerror(errno));
  }
  ~Pipe() {
    close_read();
    close_write();
  }
  Pipe(const Pipe&) = delete;
  Pipe& operator=(const Pipe&) = delete;
  int read_end() const { return fds_[0]; }
  int write_end() const { return fds_[1]; }
  void close_read() { close(0); }
  void close_write() { close(1); }

 private:
  void close(int end) {
    if (fds_[end] >= 0) ::close(fds_[end]);
    fds_[end] = -1;
  }
  int fds_[2] = {-1, -1};
};

}  // namespace

MeshingLimits meshing_limits() {
  const double triangles = std::min(kMostTriangles, available_memory_bytes() / kBytesPerTriangle);
  MeshingLimits limits;
  limits.seconds = std::max(kLeastMeshingSeconds, triangles * kMeshingSecondsPerTriangle);
  limits.bytes = kMeshingFixedBytes + triangles * kMeshingBytesPerTriangle;
  if (const auto seconds = positive_environment("ROCKDD_MESHING_SECONDS"))
    limits.seconds = *seconds;
  if (const auto bytes = positive_environment("ROCKDD_MESHING_BYTES")) limits.bytes = *bytes;
  return limits;
}

Mesh mesh_in_child_process(const std::function<Mesh()>& make, const MeshingLimits& limits,
                           const MeshSource& source, const std::string& what) {
  Pipe pipe;
  std::fflush(nullptr);  // no buffered output copied into the child
  const pid_t parent = ::getpid();
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("meshing process: fork: ") + strerror(errno));
  if (pid == 0) {
    pipe.close_read();
    run_child(make, limits, pipe.write_end(), parent);
  }
  Child child(pid);
  pipe.close_write();
  std::string reply;
  const auto deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                    std::chrono::duration<double>(limits.seconds));
  const std::string limit_text = "ROCKDD_MESHING_SECONDS, ROCKDD_MESHING_BYTES; docs/stability.md";
  const std::string too_large =
      "expected a mesh of " + what + " that Gmsh can make within the meshing memory limit of " +
      megabytes(limits.bytes) + " (" + limit_text +
      "), got one that needs more: its sizes, size fields or transfinite counts ask for more "
      "triangles than a run could hold";
  const double most_resident = limits.bytes > 0 ? resident_bytes("self") + limits.bytes : 0.0;
  const ReplyEnd end = read_reply(pipe.read_end(), pid, deadline, most_resident, reply);
  if (end != ReplyEnd::complete) {
    child.kill();
    child.wait();
    if (end == ReplyEnd::large) source.fail(too_large);
    source.fail("expected Gmsh to mesh " + what + " within the meshing time limit of " +
                format_number(limits.seconds) + " s (" + limit_text +
                "), got no mesh when it ran out: its sizes, size fields or transfinite counts "
                "ask for more triangles than a run could hold, or Gmsh is stuck on them");
  }
  const int status = child.wait();
  const std::string used = megabytes(child.peak_bytes()) +
                           (limits.bytes > 0 ? " of its " + megabytes(limits.bytes) : "");
  if (WIFSIGNALED(status))
    source.fail("expected Gmsh to mesh " + what + ", got Gmsh killed by signal " +
                std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) +
                ") in the meshing process after it used " + used +
                " of memory: a file it cannot read, or a mesh larger than its memory limit (" +
                limit_text + ")");
  if (reply.empty())
    throw std::runtime_error("the meshing process of " + what + " ended with status " +
                             std::to_string(WEXITSTATUS(status)) + " and no mesh");
  ByteReader in(std::string_view(reply).substr(1));
  switch (reply[0]) {
    case kMesh: {
      Mesh mesh;
      if (!read_mesh(in, mesh) || !in.done())
        throw std::runtime_error("the meshing process of " + what + " sent a damaged mesh");
      return mesh;
    }
    case kInputError: {
      std::string where, key, expected;
      in.text(where);
      in.text(key);
      in.text(expected);
      throw InputError(where, key, expected);
    }
    case kOutOfMemory:
      source.fail(too_large);
    case kOtherError: {
      std::string text;
      in.text(text);
      throw std::runtime_error(text);
    }
  }
  throw std::runtime_error("the meshing process of " + what + " sent an unknown reply");
}

}  // namespace rockdd
