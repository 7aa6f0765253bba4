#include "engine/scene/scene_overrides.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <string_view>

#include "engine/common/errors.hpp"
#include "engine/scene/table_reader.hpp"

namespace rockdd {
namespace {

/// One parsed `--set`: the key path split at dots and the value as a one-key TOML table.
struct Override {
  std::string text;                   // "time.dt=1e-4", as given
  std::vector<std::string> segments;  // {"time", "dt"}
  toml::table value;                  // {v = 1e-4}, its source named "--set time.dt=1e-4"
};

std::string trimmed(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  return std::string(s.substr(first, s.find_last_not_of(" \t") - first + 1));
}

/// `v = <value>` as a one-key table whose source is `source` (the override).
template <typename T>
toml::table sourced(const T& value, const std::string& source) {
  std::ostringstream literal;
  literal << toml::value<T>(value);
  return toml::parse("v = " + literal.str(), std::string_view(source));
}

/// The value as TOML; a bare word that does not parse is taken as a string, still given
/// the override as its source so that errors about it name the override.
toml::table parse_value(const std::string& value, const std::string& source) {
  try {
    toml::table parsed = toml::parse("v = " + value, std::string_view(source));
    if (parsed.size() == 1 && parsed.contains("v")) return parsed;
  } catch (const toml::parse_error&) {
  }
  // Numbers TOML refuses but a shell user writes (".5", "5.") are still numbers.
  double number = 0.0;
  const char* end = value.data() + value.size();
  const auto [stop, error] = std::from_chars(value.data(), end, number);
  if (!value.empty() && error == std::errc() && stop == end && std::isfinite(number)) {
    return sourced(number, source);
  }
  return sourced(value, source);
}

Override split(const std::string& text, const std::string& file) {
  const std::string where = file + " (--set " + text + ")";
  const auto equals = text.find('=');
  const std::string key = trimmed(std::string_view(text).substr(0, equals));
  if (equals == std::string::npos || key.empty()) {
    throw InputError(where, "", "expected --set key.path=value, got \"" + text + "\"");
  }
  Override o{
      text, {}, parse_value(trimmed(std::string_view(text).substr(equals + 1)), "--set " + text)};
  std::string_view rest = key;
  for (std::size_t dot;; rest.remove_prefix(dot + 1)) {
    dot = rest.find('.');
    o.segments.emplace_back(trimmed(rest.substr(0, dot)));
    if (o.segments.back().empty()) {
      throw InputError(where, key,
                       "expected a key path of names joined by '.', got \"" + key + "\"");
    }
    if (dot == std::string_view::npos) break;
  }
  return o;
}

/// The array index a segment names, if it is a plain decimal number.
std::optional<std::size_t> index_of(const std::string& segment) {
  if (segment.empty() || segment.size() > 9 ||
      !std::all_of(segment.begin(), segment.end(),
                   [](unsigned char c) { return std::isdigit(c); })) {
    return std::nullopt;
  }
  return std::stoul(segment);
}

void apply(toml::table& root, Override& o, const std::string& file) {
  const std::string where = file + " (--set " + o.text + ")";
  toml::node* current = &root;
  std::string path;
  for (std::size_t i = 0; i < o.segments.size(); ++i) {
    const std::string& segment = o.segments[i];
    const bool last = i + 1 == o.segments.size();
    if (auto* table = current->as_table()) {
      path += (path.empty() ? "" : ".") + segment;
      if (last) {
        table->insert_or_assign(segment, std::move(*o.value.get("v")));
        return;
      }
      if (!table->contains(segment)) {
        // A new table, sourced from the override so errors inside it name the override.
        toml::table created = toml::parse("v = {}", std::string_view("--set " + o.text));
        table->insert_or_assign(segment, std::move(*created.get("v")));
      }
      current = table->get(segment);
    } else if (auto* array = current->as_array()) {
      const auto index = index_of(segment);
      if (!index || *index >= array->size()) {
        throw InputError(where, path + "[" + segment + "]",
                         "expected an index below " + std::to_string(array->size()) +
                             " (the number of [[" + path + "]] entries), got " + segment);
      }
      path += "[" + segment + "]";
      if (last) {
        array->replace(array->cbegin() + static_cast<std::ptrdiff_t>(*index),
                       std::move(*o.value.get("v")));
        return;
      }
      current = array->get(*index);
    } else {
      throw InputError(where, path,
                       "expected a table to set a key inside, got " + describe(*current));
    }
  }
}

}  // namespace

void apply_overrides(toml::table& root, const std::vector<std::string>& overrides,
                     const std::string& file) {
  for (const std::string& text : overrides) {
    Override o = split(text, file);
    apply(root, o, file);
  }
}

}  // namespace rockdd
