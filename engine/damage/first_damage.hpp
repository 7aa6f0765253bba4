#pragma once
// Where damage first appeared in a run: summary.json's "first_damage".
#include <cstdint>

#include "engine/model/model.hpp"

namespace rockdd {

/// The elements of the first damage pass that found any damage, and where they lie.
struct FirstDamage {
  long step = 0;
  double time = 0.0;
  std::int32_t elements = 0;
  double x = 0.0, y = 0.0;  // mean reference centroid of those elements
  double spread = 0.0;      // largest distance of their centroids from that mean
};

/// The damaged elements of `model` (w > 0) as the first damage, in step `step` ending at
/// `time`.
FirstDamage locate_first_damage(const Model& model, long step, double time);

}  // namespace rockdd
