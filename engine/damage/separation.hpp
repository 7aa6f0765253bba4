#pragma once
// When damage first cuts a body into parts (issue 26's split of the Brazilian disk, the
// through-going fracture of a compression specimen).
#include <cstdint>
#include <span>
#include <vector>

#include "engine/model/edge_adjacency.hpp"
#include "engine/model/model.hpp"

namespace rockdd {

/// Watches the intact parts of a model's rock: the sets of undamaged elements (w = 0) of
/// damageable materials joined through shared sides. Elements that cannot damage (a platen, a
/// cushion, an elastic end over a support) are no part of it: bonded across a crack, they
/// would join what the crack separated. The rock is separated when more parts of at least
/// `share` of its area exist than did before any damage.
class SeparationWatch {
 public:
  /// Takes the sides shared in `model`'s mesh as it is now (undamaged) and its parts.
  SeparationWatch(const Model& model, double share = 0.1);

  /// The areas (m^2, largest first) of the intact parts of at least the share when there are
  /// more of them than at the start, else empty.
  std::vector<double> separated_parts(const Model& model) const;

 private:
  /// Areas of the intact parts of at least the share under `damage`, largest first.
  std::vector<double> large_parts(const Model& model, std::span<const double> damage) const;

  EdgeAdjacency sides_;
  std::vector<std::uint8_t> rock_;  // per element: of a damageable material
  double least_area_ = 0.0;
  std::size_t parts_at_start_ = 0;
};

}  // namespace rockdd
