#pragma once
// Outputs appear under their final name only when complete: temp file + rename.
#include <filesystem>
#include <fstream>
#include <string_view>

namespace rockdd {

/// Writes `content` to `path` through a temporary file in the same folder and a rename.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// write_file_atomically that also survives a power cut: the temporary file is fsync'ed
/// before the rename and the folder after it. Throws std::runtime_error on I/O failure.
void write_file_durably(const std::filesystem::path& path, std::string_view content);

/// A file written in pieces; it appears under its name only on commit().
/// Destroyed uncommitted, it removes its temporary file and leaves nothing behind.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  std::ofstream& stream() { return out_; }
  /// Flushes, closes and renames into place. Throws std::runtime_error on I/O failure.
  void commit();

 private:
  std::filesystem::path path_, temp_;
  std::ofstream out_;
  bool committed_ = false;
};

}  // namespace rockdd
