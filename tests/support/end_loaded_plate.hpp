#pragma once
// The end-loaded plate: the static patch-test scene of the static-analysis and stability tests.
#include <string>

#include "scene_toml.hpp"

namespace rockdd::test {

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
