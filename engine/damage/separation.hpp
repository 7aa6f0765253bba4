#pragma once
// When damage first cuts a body into parts (issue 26's split of the Brazilian disk, the
// through-going fracture of a compression specimen).
#include <cstdint>
#include <span>
#include <vector>

#include "engine/model/edge_adjacency.hpp"
#include "engine/model/model.hpp"

namespace rockdd {

/// Watches the intact parts of a model: the sets of undamaged elements (w = 0) joined through
/// shared sides. A body is separated when more parts of at least `share` of the whole area
/// exist than did before any damage.
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
  double least_area_ = 0.0;
  std::size_t parts_at_start_ = 0;
};

}  // namespace rockdd
