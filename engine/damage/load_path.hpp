#pragma once
// Whether a fractured specimen can still carry the load that a moving boundary applies: a
// chain of rock that is not fully broken and of closed contacts joins the nodes a boundary
// moves to nodes a boundary holds, along the same direction (docs/method-choices.md, "A
// specimen that falls apart").
#include <span>

#include "engine/contact/contact.hpp"
#include "engine/loading/boundary_conditions.hpp"
#include "engine/model/model.hpp"

namespace rockdd {

/// Whether the boundaries drive anything through the rock: some dof moves at an imposed
/// velocity and some dof of the same direction is held fixed.
bool has_load_path_boundaries(const BoundaryConditions& bc);

/// Whether elements with w < 1 (each joining its three nodes) and closed contacts (each
/// joining its vertex to its edge) connect a node whose x (or y) a boundary moves to a node
/// whose x (or y) a boundary holds fixed. A fully broken element joins nothing, a node shared
/// by two pieces joins them (a force passes through it), and a load applied as a force makes
/// no path: only moving boundaries are followed.
bool joins_moving_and_fixed_boundaries(const Model& model, const BoundaryConditions& bc,
                                       std::span<const Contact> contacts);

}  // namespace rockdd
