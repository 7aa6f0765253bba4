#pragma once
// A quasi-static specimen that fracture has broken into loose fragments: the run ends there
// (docs/method-choices.md, "A specimen that falls apart").
#include <cstdint>

#include "engine/model/model.hpp"

namespace rockdd {

/// A block holding less than this share of the fracturing material's area is a fragment: the
/// share below which rockdd's tools already stop counting a block as large.
inline constexpr double kFragmentShare = 0.01;

/// How the fracturing material lies in blocks.
struct BlockSpread {
  std::int32_t blocks = 0;     // blocks that hold any of it
  double largest_share = 0.0;  // of its reference area, in the largest of them
};

/// The blocks of the elements whose material can damage, weighed by reference area.
BlockSpread fracturing_block_spread(const Model& model);

/// Why a quasi-static specimen was found fallen apart.
enum class DisintegrationCause {
  fragments,     // every block of it is a fragment
  no_load_path,  // no chain of rock and closed contacts joins the moving boundary to a held one
};

/// The step after which a quasi-static specimen was fallen apart, and why.
struct Disintegration {
  long step = 0;
  double time = 0.0;
  BlockSpread spread;
  DisintegrationCause cause = DisintegrationCause::fragments;
};

/// "fragments" or "no_load_path", as summary.json names the cause.
const char* disintegration_cause_name(DisintegrationCause cause);

}  // namespace rockdd
