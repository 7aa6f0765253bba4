#include "engine/scene/table_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "engine/common/errors.hpp"

namespace rockdd {
namespace {

/// Levenshtein distance, to suggest the key a misspelling meant.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above_left = diagonal;
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, above_left + (a[i - 1] != b[j - 1])});
    }
  }
  return row[b.size()];
}

/// The allowed key closest to `key`, if close enough to be a plausible misspelling.
std::optional<std::string_view> near_match(std::string_view key,
                                           std::initializer_list<std::string_view> allowed) {
  std::optional<std::string_view> best;
  std::size_t best_distance = std::max<std::size_t>(2, key.size() / 3) + 1;
  for (std::string_view candidate : allowed) {
    const std::size_t d = edit_distance(key, candidate);
    if (d < best_distance) best = candidate, best_distance = d;
  }
  return best;
}

template <typename Words>
std::string join(const Words& words, std::string_view quote) {
  std::string text;
  for (std::string_view w : words) {
    if (!text.empty()) text += ", ";
    text.append(quote).append(w).append(quote);
  }
  return text;
}

std::string in_quotes(std::string_view s) {
  std::string text(1, '"');  // built by appends: GCC 12 warns falsely on "\"" + std::string
  text.append(s).push_back('"');
  return text;
}

/// The "expected a number ..." phrase of a range ("a number > 0").
std::string number_phrase(const Range& range) {
  const std::string bound = range.text();
  return bound.empty() ? "a number" : "a number " + bound;
}

}  // namespace

bool Range::contains(double x) const {
  const bool above_lo = lo_closed ? x >= lo : x > lo;
  const bool below_hi = hi_closed ? x <= hi : x < hi;
  return above_lo && below_hi;
}

std::string Range::text() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi) {
    return "in " + std::string(lo_closed ? "[" : "(") + format_number(lo) + ", " +
           format_number(hi) + (hi_closed ? "]" : ")");
  }
  if (has_lo) return (lo_closed ? ">= " : "> ") + format_number(lo);
  if (has_hi) return (hi_closed ? "<= " : "< ") + format_number(hi);
  return "";
}

Range above(double lo, bool closed) {
  return Range{lo, Range{}.hi, closed, false};
}

Range between(double lo, bool lo_closed, double hi, bool hi_closed) {
  return Range{lo, hi, lo_closed, hi_closed};
}

std::string describe(const toml::node& node) {
  if (const auto* s = node.as_string()) return "the string " + in_quotes(s->get());
  if (const auto* i = node.as_integer()) return std::to_string(i->get());
  if (const auto* f = node.as_floating_point()) {
    // Keep a float recognisable as one ("10.0", not "10"): it matters for integer keys.
    std::string text = format_number(f->get());
    if (std::isfinite(f->get()) && text.find_first_of(".e") == std::string::npos) text += ".0";
    return text;
  }
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  if (const auto* a = node.as_array()) {
    std::string text = "an array [";
    for (std::size_t i = 0; i < a->size(); ++i) {
      const std::string item = describe(*a->get(i));
      text += (i ? ", " : "") + (item.rfind("an array ", 0) == 0 ? item.substr(9) : item);
    }
    return text + "]";
  }
  if (node.is_table()) return "a table";
  return "a date or time";
}

std::string where_of(const toml::node& node, const std::string& file, std::size_t fallback_line) {
  const auto& source = node.source();
  if (source.path && source.path->rfind("--set ", 0) == 0) return file + " (" + *source.path + ")";
  const std::size_t line = source.begin.line ? source.begin.line : fallback_line;
  return line ? file + ":" + std::to_string(line) : file;
}

TableReader::TableReader(const toml::table& table, std::string path, const std::string& file,
                         DefaultsLog& defaults)
    : table_(table),
      path_(std::move(path)),
      file_(file),
      defaults_(defaults),
      line_(table.source().begin.line) {}

std::string TableReader::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

std::vector<std::string> TableReader::present(std::initializer_list<std::string_view> keys) const {
  std::vector<std::string> found;
  for (std::string_view key : keys) {
    if (has(key)) found.emplace_back(key);
  }
  return found;
}

void TableReader::allow_only(std::initializer_list<std::string_view> allowed) const {
  // Report the unknown key written first, so the message matches a top-down reading.
  const toml::key* first = nullptr;
  for (auto&& [key, node] : table_) {
    if (std::find(allowed.begin(), allowed.end(), key.str()) != allowed.end()) continue;
    if (!first || key.source().begin.line < first->source().begin.line) first = &key;
  }
  if (!first) return;
  std::string expected =
      "expected one of " + join(allowed, "") + "; got unknown key " + in_quotes(first->str());
  if (auto guess = near_match(first->str(), allowed)) {
    expected += " (did you mean " + in_quotes(*guess) + "?)";
  }
  fail(first->str(), expected);
}

void TableReader::fail(std::string_view key, const std::string& expected) const {
  const toml::node* node = find(key);
  throw InputError(where_of(node ? *node : static_cast<const toml::node&>(table_), file_, line_),
                   key_path(key), expected);
}

void TableReader::fail_table(const std::string& expected) const {
  throw InputError(where_of(table_, file_, line_), path_, expected);
}

std::optional<double> TableReader::number(std::string_view key, const Range& range) const {
  const toml::node* node = find(key);
  if (!node) return std::nullopt;
  const std::string want = "expected " + number_phrase(range) + ", got ";
  if (!node->is_number()) fail(key, want + describe(*node));
  const double x = *node->value<double>();
  if (!std::isfinite(x) || !range.contains(x)) fail(key, want + describe(*node));
  return x;
}

double TableReader::required_number(std::string_view key, const Range& range) const {
  if (auto x = number(key, range)) return *x;
  fail(key, "expected " + number_phrase(range) + ", got nothing (the key is required)");
}

double TableReader::number_or(std::string_view key, double fallback, const Range& range) {
  if (auto x = number(key, range)) return *x;
  record_default(key, format_number(fallback));
  return fallback;
}

std::optional<std::int64_t> TableReader::integer(std::string_view key, std::int64_t lo,
                                                 std::int64_t hi) const {
  const toml::node* node = find(key);
  if (!node) return std::nullopt;
  const auto* value = node->as_integer();
  // Upper bounds at or above int32 are storage limits, not part of the schema: shown only to
  // a value beyond them.
  const bool show_hi =
      hi < std::numeric_limits<std::int32_t>::max() || (value != nullptr && value->get() > hi);
  const std::string want = "expected an integer " +
                           (show_hi ? "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]"
                                    : ">= " + std::to_string(lo));
  if (!value || value->get() < lo || value->get() > hi)
    fail(key, want + ", got " + describe(*node));
  return value->get();
}

std::optional<std::string> TableReader::string(std::string_view key, bool non_empty) const {
  const toml::node* node = find(key);
  if (!node) return std::nullopt;
  const auto* value = node->as_string();
  if (!value || (non_empty && value->get().empty())) {
    fail(key, std::string("expected a ") + (non_empty ? "non-empty " : "") + "string, got " +
                  describe(*node));
  }
  return value->get();
}

std::string TableReader::required_string(std::string_view key) const {
  if (auto s = string(key)) return *s;
  fail(key, "expected a non-empty string, got nothing (the key is required)");
}

std::optional<std::string> TableReader::choice(
    std::string_view key, std::initializer_list<std::string_view> choices) const {
  const toml::node* node = find(key);
  if (!node) return std::nullopt;
  const auto* value = node->as_string();
  if (!value || std::find(choices.begin(), choices.end(), value->get()) == choices.end()) {
    fail(key, "expected one of " + join(choices, "\"") + ", got " + describe(*node));
  }
  return value->get();
}

std::string TableReader::choice_or(std::string_view key,
                                   std::initializer_list<std::string_view> choices,
                                   std::string_view fallback) {
  if (auto value = choice(key, choices)) return *value;
  record_default(key, std::string(fallback));
  return std::string(fallback);
}

std::optional<bool> TableReader::boolean(std::string_view key) const {
  const toml::node* node = find(key);
  if (!node) return std::nullopt;
  if (!node->is_boolean()) fail(key, "expected true or false, got " + describe(*node));
  return node->as_boolean()->get();
}

std::optional<Vec2> TableReader::vec2(std::string_view key) const {
  const toml::node* node = find(key);
  if (!node) return std::nullopt;
  const auto* array = node->as_array();
  const auto finite = [](const toml::node& n) {
    return n.is_number() && std::isfinite(*n.value<double>());
  };
  if (!array || array->size() != 2 || !finite(*array->get(0)) || !finite(*array->get(1))) {
    fail(key, "expected an array of 2 numbers [x, y], got " + describe(*node));
  }
  return Vec2{*array->get(0)->value<double>(), *array->get(1)->value<double>()};
}

std::optional<std::vector<std::string>> TableReader::strings(
    std::string_view key, const std::vector<std::string_view>& allowed) const {
  const toml::node* node = find(key);
  if (!node) return std::nullopt;
  const std::string want = !allowed.empty()
                               ? "expected an array of distinct strings from " + join(allowed, "\"")
                               : std::string("expected an array of distinct strings");
  const auto* array = node->as_array();
  if (!array) fail(key, want + ", got " + describe(*node));
  std::vector<std::string> items;
  for (const toml::node& item : *array) {
    const auto* s = item.as_string();
    if (!s) fail(key, want + ", got " + describe(item) + " in " + describe(*node));
    const bool known =
        allowed.empty() || std::find(allowed.begin(), allowed.end(), s->get()) != allowed.end();
    if (!known) fail(key, want + ", got unknown " + in_quotes(s->get()));
    if (std::find(items.begin(), items.end(), s->get()) != items.end()) {
      fail(key, want + ", got " + in_quotes(s->get()) + " twice");
    }
    items.push_back(s->get());
  }
  return items;
}

void TableReader::record_default(std::string_view key, std::string value) {
  defaults_.emplace_back(key_path(key), std::move(value));
}

std::vector<TableReader> table_array(TableReader& parent, std::string_view key) {
  std::vector<TableReader> readers;
  const toml::node* node = parent.find(key);
  if (!node) return readers;
  const auto* array = node->as_array();
  if (!array || !array->is_array_of_tables()) {
    parent.fail(key, "expected an array of tables [[" + parent.key_path(key) + "]], got " +
                         describe(*node));
  }
  for (std::size_t i = 0; i < array->size(); ++i) {
    readers.emplace_back(*array->get(i)->as_table(),
                         parent.key_path(key) + "[" + std::to_string(i) + "]", parent.file(),
                         parent.defaults());
  }
  return readers;
}

std::optional<TableReader> sub_table(TableReader& parent, std::string_view key) {
  const toml::node* node = parent.find(key);
  if (!node) return std::nullopt;
  if (!node->is_table()) {
    parent.fail(key, "expected a table [" + parent.key_path(key) + "], got " + describe(*node));
  }
  return TableReader(*node->as_table(), parent.key_path(key), parent.file(), parent.defaults());
}

}  // namespace rockdd
