#include "engine/mesh/msh_reader.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

namespace rockdd {

namespace {

bool white_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

}  // namespace

std::string printable_text(std::string_view text) {
  std::string shown(text.substr(0, 40));
  for (char& c : shown)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  return "\"" + shown + (text.size() > 40 ? "...\"" : "\"");
}

MshReader::MshReader(const std::filesystem::path& file, const MeshSource& source)
    : file_(file), source_(source) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  struct stat status {};
  if (fd < 0 || ::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) {
    if (fd >= 0) ::close(fd);
    source.fail("expected a readable .msh file, got " + file.string() + ": " +
                std::strerror(errno));
  }
  size_ = static_cast<std::size_t>(status.st_size);
  if (size_ > 0) {
    void* mapped = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    if (mapped == MAP_FAILED) {
      ::close(fd);
      source.fail("expected a readable .msh file, got " + file.string() + ": " +
                  std::strerror(errno));
    }
    data_ = static_cast<const char*>(mapped);
  }
  ::close(fd);
}

MshReader::~MshReader() {
  if (data_ != nullptr) ::munmap(const_cast<char*>(data_), size_);
}

void MshReader::skip_white_space() {
  while (at_ < size_ && white_space(data_[at_])) {
    if (data_[at_] == '\n') ++line_;
    ++at_;
  }
}

std::string_view MshReader::token(const char* what) {
  skip_white_space();
  last_at_ = at_;
  last_line_ = line_;
  if (at_ >= size_) fail(std::string("expected ") + what + ", got the end of the file");
  const std::size_t start = at_;
  while (at_ < size_ && !white_space(data_[at_])) ++at_;
  return {data_ + start, at_ - start};
}

const char* MshReader::raw(std::size_t size, const char* what) {
  last_at_ = at_;
  last_line_ = line_;
  if (size > size_ - at_) fail(std::string("expected ") + what + ", got the end of the file");
  const char* bytes = data_ + at_;
  at_ += size;
  return bytes;
}

std::int64_t MshReader::integer(MshField field, const char* what) {
  if (binary_) {
    if (field == MshField::int32) {
      std::int32_t value = 0;
      std::memcpy(&value, raw(sizeof value, what), sizeof value);
      return value;
    }
    std::uint64_t value = 0;
    std::memcpy(&value, raw(sizeof value, what), sizeof value);
    if (value > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
      fail(std::string("expected ") + what + ", got " + std::to_string(value));
    return static_cast<std::int64_t>(value);
  }
  const std::string_view text = token(what);
  std::int64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size())
    fail(std::string("expected ") + what + " (an integer), got " + printable_text(text));
  return value;
}

double MshReader::real(const char* what) {
  double value = 0.0;
  if (binary_) {
    std::memcpy(&value, raw(sizeof value, what), sizeof value);
  } else {
    std::string_view text = token(what);
    // Gmsh's fscanf takes a leading '+'; from_chars does not.
    const std::string_view digits = text.size() > 1 && text[0] == '+' ? text.substr(1) : text;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error != std::errc() || end != digits.data() + digits.size())
      fail(std::string("expected ") + what + " (a number), got " + printable_text(text));
  }
  if (!std::isfinite(value))
    fail(std::string("expected ") + what + " (a finite number), got " + std::to_string(value));
  return value;
}

std::optional<std::string_view> MshReader::line() {
  skip_white_space();
  last_at_ = at_;
  last_line_ = line_;
  if (at_ >= size_) return std::nullopt;
  const std::size_t start = at_;
  while (at_ < size_ && data_[at_] != '\n') ++at_;
  std::string_view text(data_ + start, at_ - start);
  if (at_ < size_) {  // the line break too: binary fields start right after it
    ++at_;
    ++line_;
  }
  while (!text.empty() && white_space(text.back())) text.remove_suffix(1);
  return text;
}

std::string MshReader::position() const {
  return (binary_ ? "byte " + std::to_string(last_at_) : "line " + std::to_string(last_line_));
}

std::string MshReader::place() const {
  if (binary_) return " (in " + file_.string() + ", byte " + std::to_string(last_at_) + ")";
  return " (in " + file_.string() + ":" + std::to_string(last_line_) + ")";
}

void MshReader::fail(const std::string& expected) const {
  source_.fail(expected + place());
}

}  // namespace rockdd
