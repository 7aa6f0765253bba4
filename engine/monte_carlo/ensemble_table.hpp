#pragma once
// mc.csv, the table of a Monte Carlo ensemble: one row per finished realization, appended by
// the parent process as each one finishes, so that a killed ensemble keeps every row it had.
//
// Every row is one write() of a whole line to a file opened with O_APPEND, then fsync: a
// killed writer leaves the row whole or absent. A re-run of a seed (after a "crashed" row)
// appends a second row; the last row of a seed is the one that counts.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rockdd {

/// One row of mc.csv.
struct EnsembleRow {
  std::uint64_t seed = 0;
  std::string status;              // "ok", "failed" (numerically) or "crashed" (no summary)
  std::vector<std::string> cells;  // the value columns' text, in the header's order; "": none
  std::string reason;              // why a run did not end ok
  /// True for a realization that ran to its end (ok or failed): resume does not redo it.
  bool completed() const { return status == "ok" || status == "failed"; }
};

/// mc.csv's content: the header "seed,status,<columns>,reason" and the rows in file order.
struct EnsembleTable {
  std::vector<std::string> columns;  // the value columns between status and reason
  std::vector<EnsembleRow> rows;
};

/// The header line of a table with `columns` (newline included).
std::string table_header(const std::vector<std::string>& columns);

/// One row as a complete CSV line (newline included); line breaks in the reason become spaces.
std::string format_row(const EnsembleRow& row);

/// Reads mc.csv. A last line without its newline (a write cut short by a crash, which the
/// single appending write makes all but impossible) is left out. Throws InputError naming
/// the file and line for a malformed header or row.
EnsembleTable read_ensemble_table(const std::filesystem::path& file);

/// The last row of every seed, sorted by seed.
std::vector<EnsembleRow> latest_rows(const std::vector<EnsembleRow>& rows);

/// Writes a whole table (header and rows) through a temporary file, fsync and rename.
void write_ensemble_table(const std::filesystem::path& file, const EnsembleTable& table);

/// mc.csv open for appending rows: created with its header when missing; a last line cut
/// short by a crash is cut off before the first new row.
class EnsembleTableAppender {
 public:
  /// Opens (or creates with the header of `columns`) `file`.
  EnsembleTableAppender(std::filesystem::path file, const std::vector<std::string>& columns);
  ~EnsembleTableAppender();
  EnsembleTableAppender(const EnsembleTableAppender&) = delete;
  EnsembleTableAppender& operator=(const EnsembleTableAppender&) = delete;
  /// Appends `row` with one write() and makes it durable (fsync). Throws std::runtime_error.
  void append(const EnsembleRow& row);
  /// The file descriptor, for worker processes to close after fork().
  int fd() const { return fd_; }

 private:
  std::filesystem::path file_;
  int fd_ = -1;
};

}  // namespace rockdd
