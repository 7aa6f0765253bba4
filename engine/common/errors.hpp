#pragma once
// The two ways a run can end badly: bad input (exit 2) or a numerical failure (exit 1).
#include <stdexcept>
#include <string>

namespace rockdd {

/// Bad input: a scene key, a mesh, a value out of range, a missing file. Exit code 2.
class InputError : public std::runtime_error {
 public:
  /// `where` is the file (and line, when known), `key` the key path, `what` what was expected.
  InputError(const std::string& where, const std::string& key, const std::string& expected)
      : std::runtime_error(where + (key.empty() ? "" : ": " + key) + ": " + expected),
        where_(where),
        key_(key),
        expected_(expected) {}
  const std::string& where() const { return where_; }
  const std::string& key() const { return key_; }
  const std::string& expected() const { return expected_; }

 private:
  std::string where_, key_, expected_;
};

/// A run that failed numerically (divergence, dt below dt_min, singular system). Exit code 1.
class RunFailure : public std::runtime_error {
 public:
  explicit RunFailure(const std::string& reason) : std::runtime_error(reason) {}
};

}  // namespace rockdd
