#include "engine/monte_carlo/ensemble_table.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "engine/common/atomic_file.hpp"
#include "engine/common/errors.hpp"

namespace rockdd {
namespace {

/// A CSV cell: quoted when it holds a comma or a quote.
std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

/// The cells of one CSV line (quoted cells unquoted); nothing when a quote is left open.
std::optional<std::vector<std::string>> split_csv_line(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      cells.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  if (quoted) return std::nullopt;
  return cells;
}

std::runtime_error io_error(const std::string& what, const std::filesystem::path& file) {
  return std::runtime_error(what + " '" + file.string() + "': " + std::strerror(errno));
}

/// Cuts `file` after its last newline: drops a row that a crash cut short.
void drop_partial_last_line(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (text.empty() || text.back() == '\n') return;
  const std::size_t keep = text.rfind('\n') + 1;  // npos + 1 = 0: not even a header
  std::filesystem::resize_file(file, keep);
}

}  // namespace

std::string table_header(const std::vector<std::string>& columns) {
  std::string line = "seed,status";
  for (const std::string& c : columns) line += ',' + csv_cell(c);
  return line + ",reason\n";
}

std::string format_row(const EnsembleRow& row) {
  std::string reason = row.reason;
  std::replace_if(
      reason.begin(), reason.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  std::string line = std::to_string(row.seed) + ',' + csv_cell(row.status);
  for (const std::string& cell : row.cells) line += ',' + csv_cell(cell);
  return line + ',' + csv_cell(reason) + '\n';
}

EnsembleTable read_ensemble_table(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "", "cannot read the Monte Carlo table");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EnsembleTable table;
  std::size_t line_number = 0, start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
    const std::string line = text.substr(start, end - start);
    const std::string where = file.string() + ":" + std::to_string(++line_number);
    const auto cells = split_csv_line(line);
    if (line_number == 1) {
      if (!cells || cells->size() < 3 || cells->front() != "seed" || (*cells)[1] != "status" ||
          cells->back() != "reason")
        throw InputError(where, "",
                         "expected the header 'seed,status,...,reason', got '" + line + "'");
      table.columns.assign(cells->begin() + 2, cells->end() - 1);
      continue;
    }
    if (!cells || cells->size() != table.columns.size() + 3)
      throw InputError(where, "",
                       "expected " + std::to_string(table.columns.size() + 3) +
                           " cells as in the header, got '" + line + "'");
    EnsembleRow row;
    const std::string& seed = cells->front();
    const auto parsed = std::from_chars(seed.data(), seed.data() + seed.size(), row.seed);
    if (seed.empty() || parsed.ec != std::errc() || parsed.ptr != seed.data() + seed.size())
      throw InputError(where, "seed", "expected a seed (integer >= 0), got '" + seed + "'");
    row.status = (*cells)[1];
    if (row.status != "ok" && row.status != "failed" && row.status != "crashed")
      throw InputError(where, "status", "expected ok, failed or crashed, got '" + row.status + "'");
    row.cells.assign(cells->begin() + 2, cells->end() - 1);
    row.reason = cells->back();
    table.rows.push_back(std::move(row));
  }
  if (line_number == 0) throw InputError(file.string(), "", "expected a header line, got none");
  return table;
}

std::vector<EnsembleRow> latest_rows(const std::vector<EnsembleRow>& rows) {
  std::map<std::uint64_t, const EnsembleRow*> last;
  for (const EnsembleRow& row : rows) last[row.seed] = &row;
  std::vector<EnsembleRow> out;
  out.reserve(last.size());
  for (const auto& [seed, row] : last) out.push_back(*row);
  return out;
}

void write_ensemble_table(const std::filesystem::path& file, const EnsembleTable& table) {
  std::string text = table_header(table.columns);
  for (const EnsembleRow& row : table.rows) text += format_row(row);
  write_file_durably(file, text);
}

EnsembleTableAppender::EnsembleTableAppender(std::filesystem::path file,
                                             const std::vector<std::string>& columns)
    : file_(std::move(file)) {
  if (std::filesystem::exists(file_)) drop_partial_last_line(file_);
  if (!std::filesystem::exists(file_) || std::filesystem::file_size(file_) == 0)
    write_ensemble_table(file_, {columns, {}});
  fd_ = ::open(file_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) throw io_error("cannot open for appending", file_);
}

EnsembleTableAppender::~EnsembleTableAppender() {
  if (fd_ >= 0) ::close(fd_);
}

void EnsembleTableAppender::append(const EnsembleRow& row) {
  const std::string line = format_row(row);
  // One write() of the whole line: with O_APPEND it lands at the end in one piece, and a
  // crash leaves the line whole or absent (never retried piecewise, which could split it).
  ssize_t written;
  do {
    written = ::write(fd_, line.data(), line.size());
  } while (written < 0 && errno == EINTR);
  if (written != static_cast<ssize_t>(line.size())) throw io_error("cannot append a row to", file_);
  if (::fsync(fd_) != 0) throw io_error("cannot flush", file_);
}

}  // namespace rockdd
