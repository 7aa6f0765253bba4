#pragma once
// Matrices that join K beside the elements' own: a contact's springs over its three nodes,
// handed to the linear system, which alone writes the global values.
#include <cstdint>
#include <vector>

#include "engine/assembly/stiffness_layout.hpp"

namespace rockdd {

/// Upper triangles (element_stiffness's order) at slots of the layout's scatter map: the
/// slot of the contact c of the layout's triples is num_elements + c.
struct SlotMatrices {
  std::vector<std::int32_t> slot;
  std::vector<double> upper;  // kElementUpperEntries per slot

  void clear() {
    slot.clear();
    upper.clear();
  }
  /// Appends `ku` at slot `s`; returns where its entries start, for the caller to fill.
  double* add(std::int32_t s) {
    slot.push_back(s);
    upper.resize(upper.size() + kElementUpperEntries, 0.0);
    return upper.data() + upper.size() - kElementUpperEntries;
  }
  std::size_t size() const { return slot.size(); }
};

}  // namespace rockdd
