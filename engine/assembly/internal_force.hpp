#pragma once
// Stress recovery and the nodal internal force it implies, f_int = sum R t A B^T sigma', with
// the strain measured in each element's co-rotated frame (kernels/corotation.hpp), and the
// element frames that the stiffness uses.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/assembly/element_coloring.hpp"
#include "engine/model/model.hpp"

namespace rockdd {

/// For displacement `u`: fills each element's `strain` and `stress` (3 per element, global
/// frame) and the nodal internal force `f_int` (2 per node). `corotational` measures strain in
/// each element's rotated frame (blocks that turn); without it, small strain, f_int = K u
/// exactly (static analysis). Deterministic for any thread count.
/// With `element_force` (6 per element), each element's nodal force is kept there too.
void compute_internal_force(const Model& model, const ElementColoring& coloring,
                            std::span<const double> u, std::span<double> strain,
                            std::span<double> stress, std::span<double> f_int,
                            bool corotational = false, std::span<double> element_force = {});

/// Recomputes the nodal force of `elements` at displacement `u` in `element_force` (6 per
/// element): after a damage pass, only the elements whose modulus changed. With `strain` and
/// `stress` (3 per element), theirs too. Bitwise what compute_internal_force gives them.
void refresh_element_forces(const Model& model, std::span<const double> u,
                            std::span<const std::int32_t> elements, std::span<double> element_force,
                            bool corotational, std::span<double> strain = {},
                            std::span<double> stress = {});

/// The elements with a node whose displacement differs between `u` and `u_from`, bit for bit:
/// those whose force a pass at `u` must recompute when it starts from one at `u_from`.
void elements_moved_between(const Model& model, std::span<const double> u_from,
                            std::span<const double> u, std::vector<std::uint8_t>& node_moved,
                            std::vector<std::int32_t>& elements);

/// f_int from the elements' nodal forces, summed in the colouring's order: bitwise what
/// compute_internal_force gives for the same element forces, for any thread count.
void sum_element_forces(const Model& model, const ElementColoring& coloring,
                        std::span<const double> element_force, std::span<double> f_int);

/// Whether any element, at displacement `u`, has turned by more than `tolerance` (rad, at most
/// 1) since its frame in K (Model::rotation) was set: whether the stiffness is stale.
bool frames_turned_past(const Model& model, std::span<const double> u, double tolerance);

/// Sets each element's stiffness frame (Model::rotation) to its rotation at displacement `u`.
void update_element_rotations(Model& model, std::span<const double> u);

/// The same for `elements` only.
void update_element_rotations(Model& model, std::span<const double> u,
                              std::span<const std::int32_t> elements);

/// Strain energy, sum of 1/2 sigma : eps t A over the elements (J).
double strain_energy(const Model& model, std::span<const double> strain,
                     std::span<const double> stress);

}  // namespace rockdd
