#pragma once
#include "engine/common/number_format.hpp"
// TableReader: typed access to one TOML table of a scene, where every error names the
// scene file and line, the full key path, and what was expected against what was found.
#include <toml++/toml.h>

#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/scene/scene.hpp"

namespace rockdd {

/// The ("key.path", "value") pairs of every default the reader chose.
using DefaultsLog = std::vector<std::pair<std::string, std::string>>;

/// An interval of accepted numbers; infinite ends are unbounded.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_closed = false;
  bool hi_closed = false;
  bool contains(double x) const;
  std::string text() const;  // "> 0", ">= 1", "in (-1, 0.5)", "in [0, 90)"
};

/// Numbers above `lo` (closed: at least `lo`).
Range above(double lo, bool closed = false);
/// Numbers between `lo` and `hi`, each end open or closed.
Range between(double lo, bool lo_closed, double hi, bool hi_closed);

/// What a node holds, for messages: `0.7`, `the string "abc"`, `an array [1, 2]`, `a table`.
std::string describe(const toml::node& node);

/// Where a node was written: "FILE:LINE", or "FILE (--set key=value)" for an override.
std::string where_of(const toml::node& node, const std::string& file, std::size_t fallback_line);

/// Reads one table of the scene; records the defaults it fills in.
class TableReader {
 public:
  /// `path` is the table's key path ("time", "material[1]"); `file` names the scene.
  TableReader(const toml::table& table, std::string path, const std::string& file,
              DefaultsLog& defaults);

  /// The table's own key path.
  const std::string& path() const { return path_; }
  /// The key path of `key` inside this table ("material[1].poisson").
  std::string key_path(std::string_view key) const;
  /// The node under `key`, or null.
  const toml::node* find(std::string_view key) const { return table_.get(key); }
  /// Whether `key` is present.
  bool has(std::string_view key) const { return find(key) != nullptr; }
  /// The keys of `keys` this table has, in the order given.
  std::vector<std::string> present(std::initializer_list<std::string_view> keys) const;
  /// Rejects any key outside `allowed`, naming the first one in the file and a near match.
  void allow_only(std::initializer_list<std::string_view> allowed) const;

  /// Throws InputError at `key` (its line if present, else the table's).
  [[noreturn]] void fail(std::string_view key, const std::string& expected) const;
  /// Throws InputError about the table as a whole.
  [[noreturn]] void fail_table(const std::string& expected) const;

  /// A finite number (integers accepted) inside `range`, if present.
  std::optional<double> number(std::string_view key, const Range& range) const;
  /// As number(), but the key must be present.
  double required_number(std::string_view key, const Range& range) const;
  /// As number(); when absent, `fallback` is used and recorded as a default.
  double number_or(std::string_view key, double fallback, const Range& range);
  /// An integer (a float is refused) in [lo, hi], if present.
  std::optional<std::int64_t> integer(std::string_view key, std::int64_t lo, std::int64_t hi) const;
  /// A string, if present; `non_empty` refuses "".
  std::optional<std::string> string(std::string_view key, bool non_empty = true) const;
  /// As string(), but the key must be present.
  std::string required_string(std::string_view key) const;
  /// One of `choices`, if present.
  std::optional<std::string> choice(std::string_view key,
                                    std::initializer_list<std::string_view> choices) const;
  /// One of `choices`; when absent, `fallback` is used and recorded as a default.
  std::string choice_or(std::string_view key, std::initializer_list<std::string_view> choices,
                        std::string_view fallback);
  /// A boolean, if present.
  std::optional<bool> boolean(std::string_view key) const;
  /// An array of two finite numbers [x, y], if present.
  std::optional<Vec2> vec2(std::string_view key) const;
  /// An array of distinct strings, each one of `allowed` (any string when `allowed` is empty).
  std::optional<std::vector<std::string>> strings(
      std::string_view key, const std::vector<std::string_view>& allowed) const;
  /// Records a default for `key` in the defaults log.
  void record_default(std::string_view key, std::string value);

  /// The table's line in the scene file (0 when unknown).
  std::size_t line() const { return line_; }
  /// The underlying table.
  const toml::table& table() const { return table_; }
  /// The scene file's name as the user gave it.
  const std::string& file() const { return file_; }
  /// The defaults log this reader appends to.
  DefaultsLog& defaults() { return defaults_; }

 private:
  const toml::table& table_;
  std::string path_;
  const std::string& file_;
  DefaultsLog& defaults_;
  std::size_t line_;
};

/// Readers for each table of the array of tables `key` of `parent` ("material[0]", ...);
/// empty when absent. Refuses a plain table or an array of non-tables.
std::vector<TableReader> table_array(TableReader& parent, std::string_view key);
/// A reader for the sub-table `key` of `parent`, if present; refuses a non-table.
std::optional<TableReader> sub_table(TableReader& parent, std::string_view key);

}  // namespace rockdd
