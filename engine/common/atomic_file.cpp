#include "engine/common/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

namespace rockdd {
namespace {

/// `.<name>.tmp.<pid>.<n>` beside the target, so the rename stays within one file system;
/// the count keeps two threads of one process that write the same file apart.
std::filesystem::path temp_path_for(const std::filesystem::path& path) {
  static std::atomic<unsigned long> count{0};
  // Built piecewise: `"." + string` trips a false -Wrestrict in GCC 12.
  std::string name(".");
  name += path.filename().string();
  name += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(count++);
  return path.parent_path() / name;
}

/// Error naming the file and the system's reason; errno is unset (0) for some stream failures.
std::runtime_error io_error(const std::string& what, const std::filesystem::path& path, int err) {
  const std::string reason = err != 0 ? std::strerror(err) : "I/O error";
  return std::runtime_error(what + " '" + path.string() + "': " + reason);
}

/// Writes all of `content` to `fd` (write() may take less than asked); false on error.
bool write_all(int fd, std::string_view content) {
  while (!content.empty()) {
    const ssize_t n = ::write(fd, content.data(), content.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    content.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

}  // namespace

void write_file_durably(const std::filesystem::path& path, std::string_view content) {
  const std::filesystem::path temp = temp_path_for(path);
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw io_error("cannot create temporary file for", path, errno);
  const bool written = write_all(fd, content) && ::fsync(fd) == 0;
  const int err = errno;
  ::close(fd);
  std::error_code ec;
  if (!written) {
    std::filesystem::remove(temp, ec);
    throw io_error("cannot write", path, err);
  }
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    throw io_error("cannot rename temporary file to", path, ec.value());
  }
  // The rename itself is durable only once the folder is.
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
  const int dir_fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    ::fsync(dir_fd);
    ::close(dir_fd);
  }
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  AtomicFile file(path);
  file.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  file.commit();
}

AtomicFile::AtomicFile(std::filesystem::path path)
    : path_(std::move(path)), temp_(temp_path_for(path_)) {
  errno = 0;
  out_.open(temp_, std::ios::out | std::ios::binary | std::ios::trunc);
  if (!out_) throw io_error("cannot create temporary file for", path_, errno);
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;  // a destructor must not throw; a leftover dot-file is harmless
  std::filesystem::remove(temp_, ignored);
}

void AtomicFile::commit() {
  if (committed_) throw std::runtime_error("file '" + path_.string() + "' committed twice");
  errno = 0;
  out_.flush();
  if (!out_) throw io_error("cannot write", path_, errno);
  out_.close();
  if (out_.fail()) throw io_error("cannot close", path_, errno);
  std::error_code ec;
  std::filesystem::rename(temp_, path_, ec);
  if (ec) throw io_error("cannot rename temporary file to", path_, ec.value());
  committed_ = true;
}

}  // namespace rockdd
