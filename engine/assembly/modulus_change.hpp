#pragma once
// The change of the stiffness matrix when element moduli change (a damage pass), as low-rank
// terms that CholmodSolver::update folds into the factor instead of refactorizing.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/assembly/low_rank_terms.hpp"
#include "engine/assembly/stiffness_layout.hpp"
#include "engine/model/model.hpp"

namespace rockdd {

/// The elements whose damage differs from damage_before[e] (a damage pass's change).
void changed_elements(const Model& model, std::span<const double> damage_before,
                      std::vector<std::int32_t>& changed);

/// K(after) - K(before) = added C C^T - removed C C^T, where the damage of each element of
/// `changed` went from damage_before[e] to model.damage[e]: each element whose modulus changed
/// contributes its rank-3 stiffness factor (kernels::cst_stiffness_factor, in its co-rotated
/// frame) scaled by sqrt(|E(after) - E(before)|). Rows are the equations of `equation`
/// (prescribed dofs dropped). Fills `added` and `removed` (cleared first).
void modulus_change_terms(const Model& model, std::span<const std::int32_t> equation,
                          std::span<const std::int32_t> changed,
                          std::span<const double> damage_before, LowRankTerms& added,
                          LowRankTerms& removed);

/// values += K(after) - K(before) for the same change, element by element into the layout's
/// entries: the assembled matrix follows the factor that update() changed, without
/// reassembling the elements that did not change.
void add_modulus_change(const Model& model, const StiffnessLayout& layout,
                        std::span<const std::int32_t> changed,
                        std::span<const double> damage_before, std::span<double> values);

}  // namespace rockdd
