#pragma once
// Command-line overrides (`--set key.path=value`) applied to a parsed scene before validation.
#include <toml++/toml.h>

#include <string>
#include <vector>

namespace rockdd {

/// Sets each `key.path=value` of `overrides` in `root`, in order. The value is read as a TOML
/// value (a bare word that is not TOML becomes a string); a numeric segment indexes an array
/// of tables (`material.0.young`). Missing tables are created; a missing array element is an
/// InputError naming `file` and the override. The set nodes remember the override as their
/// source, so later validation errors name `--set key.path=value` instead of a file line.
void apply_overrides(toml::table& root, const std::vector<std::string>& overrides,
                     const std::string& file);

}  // namespace rockdd
