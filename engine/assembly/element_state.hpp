#pragma once
// Small per-element helpers shared by assembly and stress recovery.
#include <algorithm>
#include <cstdint>
#include <span>

#include "engine/model/model.hpp"
#include "kernels/cst.hpp"

namespace rockdd {

/// Gathers the 6 coordinates of element e from a 2-per-node array.
inline void gather_element(std::span<const std::int32_t> conn, std::int32_t e,
                           std::span<const double> field, double out[6]) {
  for (int k = 0; k < 3; ++k) {
    const std::int32_t n = conn[3 * e + k];
    out[2 * k] = field[2 * n];
    out[2 * k + 1] = field[2 * n + 1];
  }
}

}  // namespace rockdd
