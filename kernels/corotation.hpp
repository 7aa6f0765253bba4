#pragma once
// Co-rotational CST: the element's rigid rotation is taken out before the strain is measured
// and put back on its forces and stiffness, so a block that turns through large angles keeps
// zero stress and its area (METHOD.md "Time integration"). Pure functions over plain arrays,
// with the conventions of cst.hpp; theta is counter-clockwise, in radians,
// passed as its Rotation (cos, sin).

#include <cmath>

namespace rockdd::kernels {

/// cos and sin of an element's rotation, computed once: the functions below take them
/// instead of the angle so that an element's several turns share one sincos.
struct Rotation {
  double cs = 1.0, sn = 0.0;
  Rotation() = default;
  explicit Rotation(double theta) : cs(std::cos(theta)), sn(std::sin(theta)) {}
  Rotation(double c, double s) : cs(c), sn(s) {}
};

/// Rotation of the element from reference xy0 to current xy: the angle of the rotation
/// factor R of the polar decomposition F = R U of its deformation gradient.
double element_rotation(const double xy0[6], const double xy[6]);

/// The same rotation as its (cos, sin), without trigonometry: the normalised
/// (F11 + F22, F21 - F12). Equal to Rotation(element_rotation(xy0, xy)) up to round-off.
Rotation element_rotation_factor(const double xy0[6], const double xy[6]);

/// Whether the element's rotation from xy0 to xy lies within `bound` (rad, at most 1) of the
/// frame `frame` for certain, without trigonometry: the turn's tangent, taken relative to the
/// frame from the unnormalised rotation factor, is under bound / 2. False says only that the
/// exact angle must decide (element_rotation). The frame check runs its batch form
/// (corotated_cst_batch.hpp), which tests/test_corotation holds to this one's decisions.
bool turned_within(const double xy0[6], const double xy[6], Rotation frame, double bound);

/// Displacement left once the rotation theta and the translation are taken out, in the
/// reference frame: u_k = R^T (x_k - x_c) - (X_k - X_c), c the centroid.
void corotated_displacement(const double xy0[6], const double xy[6], Rotation r, double u[6]);

/// v_k <- R v_k for the three nodal 2-vectors of v[6].
void rotate_nodal(Rotation r, double v[6]);

/// k <- T k T^T, T = diag(R, R, R): an element matrix from the element frame to the global one.
void rotate_element_matrix(Rotation r, double k[36]);

/// A symmetric tensor {xx, yy, xy} from the element frame to the global one: R s R^T.
void rotate_tensor(Rotation r, double s[3]);

}  // namespace rockdd::kernels
