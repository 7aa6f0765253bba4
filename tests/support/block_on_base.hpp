#pragma once
// A block on a base, two bodies meshed apart under gravity with a joint between them: the
// scene of the contact, block-motion and stability tests.
#include <string>

#include "rectangle_geo.hpp"
#include "scene_toml.hpp"

namespace rockdd::test {

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

}  // namespace rockdd::test
