#pragma once
// Constant-strain triangle (CST): pure functions over plain arrays.
//
// Conventions, shared by every caller:
//  - xy[6] = {x0, y0, x1, y1, x2, y2}, nodes counter-clockwise (positive area).
//  - u[6]  = {ux0, uy0, ux1, uy1, ux2, uy2}; element dof order matches xy.
//  - strain eps[3] = {exx, eyy, gxy} with gxy the engineering shear strain (2 exy).
//  - stress sig[3] = {sxx, syy, sxy}; tension positive.
//  - 6x6 element matrices are row-major, k[6 * a + b].
//  - t is the thickness; every matrix and force scales with it.
//  - Element integrals use |A|, so a clockwise triangle gets the same k and f as its
//    counter-clockwise reordering; a degenerate triangle (A = 0) is the caller's to reject.

#include "kernels/material.hpp"

namespace rockdd::kernels {

/// Signed area of the triangle (positive when counter-clockwise).
double cst_signed_area(const double xy[6]);

/// Shape-function derivatives: b[i] = dN_i/dx * 2A, c[i] = dN_i/dy * 2A; returns signed area.
double cst_gradients(const double xy[6], double b[3], double c[3]);

/// The three distinct entries of an isotropic D: normal = D11 = D22, cross = D12 = D21,
/// shear = D33 (the others are zero).
struct IsotropicModuli {
  double normal, cross, shear;
};

/// D's entries for Young's modulus `young` and Poisson ratio `poisson`. Requires
/// -1 < poisson < 0.5: plane strain divides by (1 - 2 nu), so nu = 0.5 must be rejected by
/// the caller (nu = 0.4999 still gives a finite D).
IsotropicModuli isotropic_moduli(double young, double poisson, PlaneKind plane);

/// Isotropic elasticity matrix D (3x3 row-major) mapping {exx, eyy, gxy} to {sxx, syy, sxy},
/// from isotropic_moduli.
void elasticity_matrix(double young, double poisson, PlaneKind plane, double d[9]);

/// Element stiffness k = t A B^T D B (6x6 row-major).
void cst_stiffness(const double xy[6], const double d[9], double t, double k[36]);

/// Entries of the upper triangle of a 6x6 element matrix: (a, b) with a <= b.
inline constexpr int kUpperEntries = 21;

/// The upper triangle of cst_stiffness for an isotropic D, row by row (k[0][0], k[0][1], ...,
/// k[0][5], k[1][1], ...): what assembly adds. Works from D's three distinct entries in 2x2
/// blocks per node pair and writes 21 entries, not 36 (bench_kernels: 2.2x the rate of
/// elasticity_matrix plus cst_stiffness). Equal to cst_stiffness up to round-off.
void cst_isotropic_stiffness_upper(const double xy[6], const IsotropicModuli& d, double t,
                                   double ku[kUpperEntries]);

/// A factor of the element stiffness, k = W W^T with W 6x3 (row-major, w[3 * a + j]):
/// W = sqrt(t |A|) B^T L for D = L L^T. k has rank 3 (its null space is the rigid motions),
/// so a change of the element's modulus changes K by a rank-3 term that a Cholesky factor can
/// absorb by an update instead of a refactorization. Needs D positive definite (nu < 0.5).
void cst_stiffness_factor(const double xy[6], const double d[9], double t, double w[18]);

/// Strain of the element for nodal displacements u.
void cst_strain(const double xy[6], const double u[6], double eps[3]);

/// Stress from strain: sig = D eps.
void cst_stress(const double d[9], const double eps[3], double sig[3]);

/// Nodal internal force f = t A B^T sig (6 values, in element dof order).
void cst_internal_force(const double xy[6], const double sig[3], double t, double f[6]);

/// Lumped mass per node (rho t A / 3): the same for the x and y dof of each node.
double cst_lumped_mass(double area, double density, double t);

/// Consistent mass (6x6 row-major): rho t A / 12 * [2 1 1; 1 2 1; 1 1 2] per direction.
void cst_consistent_mass(double area, double density, double t, double m[36]);

/// Out-of-plane strain: 0 in plane strain, -nu/(1-nu)(exx+eyy) in plane stress.
double out_of_plane_strain(const double eps[3], double poisson, PlaneKind plane);

/// Out-of-plane stress: nu (sxx+syy) in plane strain, 0 in plane stress.
double out_of_plane_stress(const double sig[3], double poisson, PlaneKind plane);

}  // namespace rockdd::kernels
