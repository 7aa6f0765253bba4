#pragma once
// Reading a .msh's fields as Gmsh 4.8 reads them, for the checks that run before Gmsh does:
// in an ASCII file numbers separated by any white space, line breaks included (Gmsh's
// fscanf), in a binary file the raw 4-byte ints, 8-byte size_t and doubles of the host. Every
// read knows where it was in the file, so a message can point at the line (ASCII) or the
// byte (binary).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "engine/mesh/mesh_errors.hpp"

namespace rockdd {

/// The width of a binary field: Gmsh writes dimensions, entity tags, element types and flags
/// as int, counts and node and element tags as size_t. ASCII files hold both as text.
enum class MshField { int32, size };

/// The fields of one .msh file, read in order. The file is mapped, not copied.
class MshReader {
 public:
  /// Maps `file`; throws InputError (through `source`) when it cannot be read. Reading starts
  /// at its first byte, as text, until binary() is called.
  MshReader(const std::filesystem::path& file, const MeshSource& source);
  ~MshReader();
  MshReader(const MshReader&) = delete;
  MshReader& operator=(const MshReader&) = delete;

  /// From here on, numbers are raw binary fields (after the header of a binary file).
  void binary() { binary_ = true; }
  bool is_binary() const { return binary_; }

  /// An integer field. ASCII: a token of an optional '-' and digits that fits in 64 bits.
  /// Binary: a 4-byte int or an 8-byte size_t below 2^63. Fails naming `what` otherwise.
  std::int64_t integer(MshField field, const char* what);
  /// A number field: ASCII a token that is all a number, binary an 8-byte double; finite.
  double real(const char* what);
  /// The next line that is not blank, without its trailing white space (section names, which
  /// are text in both encodings), its line break read too; nullopt at the end of the file.
  std::optional<std::string_view> line();

  /// Where the last field or line read starts: "line N", or "byte N" past the header of a
  /// binary file.
  std::string position() const;
  /// The same with the file: " (in FILE:LINE)", or " (in FILE, byte N)".
  std::string place() const;
  /// Fails with `expected` and the place of the last read.
  [[noreturn]] void fail(const std::string& expected) const;
  const std::filesystem::path& file() const { return file_; }

 private:
  /// The next white-space separated token (ASCII); fails naming `what` at the end of the file.
  std::string_view token(const char* what);
  /// The next `size` raw bytes (binary); fails naming `what` at the end of the file.
  const char* raw(std::size_t size, const char* what);
  void skip_white_space();

  std::filesystem::path file_;
  MeshSource source_;
  const char* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t at_ = 0;         // the next byte to read
  std::size_t line_ = 1;       // the line of `at_`
  std::size_t last_at_ = 0;    // where the last read started
  std::size_t last_line_ = 1;  // and its line
  bool binary_ = false;
};

/// At most 40 characters of `text`, control and non-ASCII bytes shown as '?', quoted.
std::string printable_text(std::string_view text);

}  // namespace rockdd
