#pragma once
// TOML tables that many test scenes state alike ([scene], a rectangle [mesh], [[material]],
// [[joint]], a fixed [[boundary]], [[probe]], [output]): each takes the numbers a test is about,
// so that the test still shows them, and returns TOML text for run_scene_text and
// scene_from_text.
#include <array>
#include <initializer_list>
#include <string>

#include "engine/common/number_format.hpp"

namespace rockdd::test {

/// A TOML float that reads back as exactly `value` ("2600.0", "1e+10"): a float key stays a
/// float, never an integer, and no digit is lost.
inline std::string toml_number(double value) {
  std::string text = format_number(value);
  if (text.find_first_of(".eni") == std::string::npos) text += ".0";
  return text;
}

/// A TOML array of strings: ["x", "y"].
inline std::string toml_strings(std::initializer_list<const char*> items) {
  std::string text = "[";
  for (const char* item : items)
    text += (text.size() > 1 ? ", \"" : "\"") + std::string(item) + "\"";
  return text + "]";
}

/// [scene] with its name and analysis ("" leaves the key out: static); `more` adds keys
/// (gravity, plane, thickness), one a line.
inline std::string scene_table(const std::string& name, const std::string& analysis,
                               const std::string& more = "") {
  return "\n[scene]\nname = \"" + name + "\"\n" +
         (analysis.empty() ? "" : "analysis = \"" + analysis + "\"\n") + more;
}

/// [mesh] of the built-in rectangle `width` x `height` (m), `divisions` elements along x and y.
inline std::string rectangle_mesh(double width, double height, std::array<int, 2> divisions) {
  return "[mesh]\nshape = \"rectangle\"\nsize = [" + toml_number(width) + ", " +
         toml_number(height) + "]\ndivisions = [" + std::to_string(divisions[0]) + ", " +
         std::to_string(divisions[1]) + "]\n";
}

/// [mesh] of the built-in rectangle `width` x `height` (m), unstructured at `element_size`.
inline std::string rectangle_mesh(double width, double height, double element_size) {
  return "[mesh]\nshape = \"rectangle\"\nsize = [" + toml_number(width) + ", " +
         toml_number(height) + "]\nelement_size = " + toml_number(element_size) + "\n";
}

/// [[material]] of `body` (kg/m^3, Pa): "" leaves body out, the reader's every body; `more`
/// adds keys (strengths, heterogeneity), one a line.
inline std::string material(const std::string& body, double density, double young, double poisson,
                            const std::string& more = "") {
  return "[[material]]\n" + (body.empty() ? "" : "body = \"" + body + "\"\n") +
         "density = " + toml_number(density) + "\nyoung = " + toml_number(young) +
         "\npoisson = " + toml_number(poisson) + "\n" + more;
}

/// [[joint]] between bodies `a` and `b` with its friction angle (degrees).
inline std::string joint(const std::string& a, const std::string& b, double friction_angle) {
  return "[[joint]]\nbetween = [\"" + a + "\", \"" + b +
         "\"]\nfriction_angle = " + toml_number(friction_angle) + "\n";
}

/// [[boundary]] holding the named set `on` fixed along `axes`.
inline std::string fixed(const std::string& on,
                         std::initializer_list<const char*> axes = {"x", "y"}) {
  return "[[boundary]]\non = \"" + on + "\"\nfix = " + toml_strings(axes) + "\n";
}

/// [[probe]] `name` of the named curve or point set `on`, writing `fields` to history.csv.
inline std::string probe_on(const std::string& name, const std::string& on,
                            std::initializer_list<const char*> fields) {
  return "[[probe]]\nname = \"" + name + "\"\non = \"" + on +
         "\"\nfields = " + toml_strings(fields) + "\n";
}

/// [[probe]] `name` of the whole body `body` (its mean motion), writing `fields`.
inline std::string probe_body(const std::string& name, const std::string& body,
                              std::initializer_list<const char*> fields) {
  return "[[probe]]\nname = \"" + name + "\"\nbody = \"" + body +
         "\"\nfields = " + toml_strings(fields) + "\n";
}

/// [output] with every = 0: history.csv and summary.json only, no VTU frame to write; `dir`
/// ("" leaves it out) is overridden by the tests' out_root anyway.
inline std::string no_frames(const std::string& dir = "") {
  return "[output]\n" + (dir.empty() ? "" : "dir = \"" + dir + "\"\n") + "every = 0\n";
}

}  // namespace rockdd::test
