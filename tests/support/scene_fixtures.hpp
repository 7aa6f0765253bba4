#pragma once
// Scene fixtures shared by the engine tests: the TOML tables that many scenes state alike
// (material, fixed edge, probe, output), and the named scenes that several test files run (a
// block on a base, the end-loaded plate). Each takes the numbers a test is about, so that the
// test still shows them; they return TOML text for run_scene_text and scene_from_text.
#include <array>
#include <charconv>
#include <initializer_list>
#include <string>

#include "test_support.hpp"

namespace rockdd::test {

/// A TOML float that reads back as exactly `value` ("2600.0", "1e+10"): a float key stays a
/// float, never an integer, and no digit is lost.
inline std::string toml_number(double value) {
  char buffer[32];
  const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string text(buffer, result.ptr);
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

// --- A block on a base --------------------------------------------------------------------------

/// An axis-aligned rectangle [x0, x1] x [y0, y1] (m) meshed at `element_size` (m).
struct Box {
  double x0, y0, x1, y1, element_size;
};

/// Gmsh text of a block above or on a base, each meshed on its own (two blocks): surface 1
/// is body "base", surface 11 body "block", and the base's bottom edge is "base_bottom".
inline std::string block_on_base_geo(const Box& base, const Box& block) {
  return rectangle_geo(0, base.x0, base.y0, base.x1, base.y1, base.element_size) +
         rectangle_geo(10, block.x0, block.y0, block.x1, block.y1, block.element_size) +
         "Physical Surface(\"base\") = {1};\nPhysical Surface(\"block\") = {11};\n"
         "Physical Curve(\"base_bottom\") = {1};\n";
}

/// The scene of a block on a base (the bodies of block_on_base_geo, in the file `geo`) under
/// gravity g = 10 m/s^2 down: one joint between base and block, "base_bottom" fixed. What
/// differs between the tests is named here; `more` holds their [[initial]] and [[probe]] tables.
struct BlockOnBaseScene {
  std::string name = "block-on-base";
  std::string analysis = "dynamic";
  std::string plane = "";                 // "" leaves it out (plane stress)
  std::string time = "";                  // the [time] table's lines
  std::string geo = "block_on_base.geo";  // the Gmsh file beside the scene
  std::string materials = material("*", 2600.0, 10e9, 0.25);
  double friction_angle = 0.0;  // of the joint, degrees
  std::string more = "";        // [[initial]] and [[probe]] tables
  std::string output = no_frames();

  /// The scene as TOML text.
  std::string toml() const {
    return scene_table(
               name, analysis,
               (plane.empty() ? "" : "plane = \"" + plane + "\"\n") + "gravity = [0.0, -10.0]\n") +
           "[time]\n" + time + "\n[mesh]\ngeo = \"" + geo + "\"\n" + materials +
           joint("base", "block", friction_angle) + fixed("base_bottom") + more + output;
  }
};

// --- The end-loaded plate -----------------------------------------------------------------------

/// A 2 m x 1 m plate, 0.5 m thick, meshed unstructured at 0.13 m (E = 40 GPa, 2500 kg/m^3),
/// static: left edge on rollers (x fixed), bottom-left corner pinned, and its right end
/// `loading`, by default pulled with a total force F = 1e6 N: sigma_xx = F / (h t) = 2 MPa.
struct EndLoadedPlate {
  std::string name = "uniaxial";
  std::string plane = "stress";  // or "strain"
  double poisson = 0.25;
  static constexpr double young = 40e9, force = 1e6, length = 2.0, height = 1.0, thickness = 0.5;

  std::string loading = "[[load]]\non = \"right\"\nforce = [" + toml_number(force) + ", 0.0]\n";
  std::string probes = "";  // [[probe]] tables

  /// The scene as TOML text.
  std::string toml() const {
    return scene_table(name, "static",
                       "plane = \"" + plane + "\"\nthickness = " + toml_number(thickness) + "\n") +
           rectangle_mesh(length, height, 0.13) + material("body", 2500.0, young, poisson) +
           fixed("left", {"x"}) + fixed("bottom_left") + loading + probes + no_frames();
  }
};

}  // namespace rockdd::test
