#pragma once
// The co-rotated CST's strain, stress and nodal force for a batch of elements at once, lane by
// lane (structure of arrays), so that the compiler computes several elements per instruction.
// Bitwise what the one-element kernels give (corotation.hpp and cst.hpp, in the order
// element_rotation_factor, corotated_displacement, elasticity_matrix, cst_strain, cst_stress,
// cst_internal_force, rotate_nodal, rotate_tensor): every lane performs the same operations in
// the same order, and a packed IEEE operation rounds each lane as its scalar form does
// (tests/test_corotation checks it bit for bit).
#include "kernels/material.hpp"

namespace rockdd::kernels {

/// Elements per batch.
inline constexpr int kCstBatch = 16;

/// A batch of elements, one lane each: the inputs of corotated_cst_forces and its outputs.
struct CstBatch {
  double xy0[6][kCstBatch];  // reference corners, cst.hpp's order
  double x[6][kCstBatch];    // current corners
  double young[kCstBatch];   // the damaged modulus E
  double poisson[kCstBatch];
  double strain[3][kCstBatch];  // global frame, engineering shear
  double stress[3][kCstBatch];  // global frame
  double force[6][kCstBatch];   // nodal force, global frame
};

/// corotation.hpp's turned_within for lanes [0, count) of `batch`'s corners, each against its
/// frame (frame_cos, frame_sin): within[i] true says that lane i has turned less than `bound`
/// for certain, false that its exact angle must decide. Reads only the corners (the lanes past
/// count are overwritten with lane 0's).
void turned_within(CstBatch& batch, int count, const double frame_cos[kCstBatch],
                   const double frame_sin[kCstBatch], double bound, bool within[kCstBatch]);

/// Fills lanes [0, count) of `batch`'s outputs from their inputs (count <= kCstBatch; the
/// lanes past it are overwritten with copies of lane 0 and computed too).
void corotated_cst_forces(CstBatch& batch, int count, PlaneKind plane, double t);

}  // namespace rockdd::kernels
