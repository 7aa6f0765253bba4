#pragma once
// A 64-bit hash of byte strings, to tell whether an input changed (ensemble manifests, the
// mesh cache).
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace rockdd {

/// FNV-1a, 64 bits: a change detector, not a defence against forgery.
class Fnv1a {
 public:
  /// Adds `bytes` with their length first, so that ("ab", "c") and ("a", "bc") differ.
  void add(std::string_view bytes) {
    const std::string length = std::to_string(bytes.size()) + ':';
    mix(length);
    mix(bytes);
  }
  std::uint64_t value() const { return state_; }
  std::string hex() const {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(state_));
    return text;
  }

 private:
  void mix(std::string_view bytes) {
    for (const char c : bytes) {
      state_ ^= static_cast<unsigned char>(c);
      state_ *= 0x100000001b3ULL;
    }
  }
  std::uint64_t state_ = 0xcbf29ce484222325ULL;
};

}  // namespace rockdd
