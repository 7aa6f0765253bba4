#pragma once
// Plain values and arrays as bytes in the host's layout, for what rockdd writes for itself:
// mesh cache entries and the mesh a meshing process hands back. Not a file format to share:
// a reader on another machine must check a byte-order mark first.
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace rockdd {

class ByteWriter {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void text(std::string_view s) {
    value<std::uint64_t>(s.size());
    bytes_.append(s);
  }
  template <class T>
  void array(std::span<const T> v) {
    value<std::uint64_t>(v.size());
    bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  template <class T>
  void array(const std::vector<T>& v) {
    array(std::span<const T>(v));
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

/// Reads what a ByteWriter wrote; every read returns false, reading nothing more, when the
/// bytes are too short for it.
class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : rest_(bytes) {}
  template <class T>
  bool value(T& v) {
    if (rest_.size() < sizeof v) return false;
    std::memcpy(&v, rest_.data(), sizeof v);
    rest_.remove_prefix(sizeof v);
    return true;
  }
  bool text(std::string& s) {
    std::uint64_t n = 0;
    if (!value(n) || n > rest_.size()) return false;
    s.assign(rest_.substr(0, n));
    rest_.remove_prefix(n);
    return true;
  }
  template <class T>
  bool array(std::vector<T>& v) {
    std::uint64_t n = 0;
    if (!value(n) || n > rest_.size() / sizeof(T)) return false;
    v.resize(n);
    std::memcpy(v.data(), rest_.data(), n * sizeof(T));
    rest_.remove_prefix(n * sizeof(T));
    return true;
  }
  /// Reads an array and compares it with `expected`, without a copy.
  template <class T>
  bool same_array(std::span<const T> expected) {
    std::uint64_t n = 0;
    if (!value(n) || n != expected.size() || n > rest_.size() / sizeof(T)) return false;
    const std::size_t size = n * sizeof(T);
    if (size > 0 && std::memcmp(rest_.data(), expected.data(), size) != 0) return false;
    rest_.remove_prefix(size);
    return true;
  }
  bool done() const { return rest_.empty(); }

 private:
  std::string_view rest_;
};

}  // namespace rockdd
