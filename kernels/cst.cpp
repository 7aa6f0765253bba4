#include "kernels/cst.hpp"

#include <cmath>

namespace rockdd::kernels {

// Every integral over the element is taken over |A|, while B = Bhat / (2A) uses the signed
// area, so the matrices are right for either node order; detecting an inverted element is
// the caller's job (cst_signed_area).

double cst_signed_area(const double xy[6]) {
  return 0.5 * ((xy[2] - xy[0]) * (xy[5] - xy[1]) - (xy[4] - xy[0]) * (xy[3] - xy[1]));
}

double cst_gradients(const double xy[6], double b[3], double c[3]) {
  // Paper eq. (11) with (i, j, m) cyclic: b_i = y_j - y_m, c_i = x_m - x_j.
  b[0] = xy[3] - xy[5];
  b[1] = xy[5] - xy[1];
  b[2] = xy[1] - xy[3];
  c[0] = xy[4] - xy[2];
  c[1] = xy[0] - xy[4];
  c[2] = xy[2] - xy[0];
  return 0.5 * (b[1] * c[2] - b[2] * c[1]);
}

IsotropicModuli isotropic_moduli(double young, double poisson, PlaneKind plane) {
  // The shear modulus is written as E / (2 (1 + nu)) in both modes: the textbook form
  // E / ((1 + nu)(1 - 2 nu)) * (1 - 2 nu) / 2 loses digits as nu approaches 1/2.
  const double nu = poisson;
  const double shear = young / (2.0 * (1.0 + nu));
  if (plane == PlaneKind::stress) {
    const double f = young / (1.0 - nu * nu);
    return {f, f * nu, shear};
  }
  const double f = young / ((1.0 + nu) * (1.0 - 2.0 * nu));
  return {f * (1.0 - nu), f * nu, shear};
}

void elasticity_matrix(double young, double poisson, PlaneKind plane, double d[9]) {
  const IsotropicModuli m = isotropic_moduli(young, poisson, plane);
  d[0] = m.normal;
  d[1] = m.cross;
  d[2] = 0.0;
  d[3] = m.cross;
  d[4] = m.normal;
  d[5] = 0.0;
  d[6] = 0.0;
  d[7] = 0.0;
  d[8] = m.shear;
}

void cst_stiffness(const double xy[6], const double d[9], double t, double k[36]) {
  double b[3], c[3];
  const double area = cst_gradients(xy, b, c);
  // k = t |A| B^T D B with B = Bhat / (2A); column a of Bhat is {b_i, 0, c_i} for the x dof
  // of node i and {0, c_i, b_i} for its y dof.
  const double scale = t / (4.0 * std::fabs(area));
  double bhat[6][3], dbhat[6][3];
  for (int i = 0; i < 3; ++i) {
    bhat[2 * i][0] = b[i];
    bhat[2 * i][1] = 0.0;
    bhat[2 * i][2] = c[i];
    bhat[2 * i + 1][0] = 0.0;
    bhat[2 * i + 1][1] = c[i];
    bhat[2 * i + 1][2] = b[i];
  }
  for (int a = 0; a < 6; ++a)
    for (int r = 0; r < 3; ++r)
      dbhat[a][r] = d[3 * r] * bhat[a][0] + d[3 * r + 1] * bhat[a][1] + d[3 * r + 2] * bhat[a][2];
  // Upper triangle mirrored, so k is exactly symmetric whatever the rounding.
  for (int a = 0; a < 6; ++a) {
    for (int bb = a; bb < 6; ++bb) {
      const double kab = scale * (bhat[a][0] * dbhat[bb][0] + bhat[a][1] * dbhat[bb][1] +
                                  bhat[a][2] * dbhat[bb][2]);
      k[6 * a + bb] = kab;
      k[6 * bb + a] = kab;
    }
  }
}

void cst_isotropic_stiffness_upper(const double xy[6], const IsotropicModuli& d, double t,
                                   double ku[kUpperEntries]) {
  double b[3], c[3];
  const double area = cst_gradients(xy, b, c);
  const double scale = t / (4.0 * std::fabs(area));
  const double normal = scale * d.normal, cross = scale * d.cross, shear = scale * d.shear;
  // With B's x column of node i {b_i, 0, c_i} and y column {0, c_i, b_i} (cst_stiffness),
  // the 2x2 block of nodes (i, j) is
  //   [normal b_i b_j + shear c_i c_j    cross b_i c_j + shear c_i b_j ]
  //   [cross c_i b_j + shear b_i c_j     normal c_i c_j + shear b_i b_j].
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {  // row x_i
      ku[n++] = normal * b[i] * b[j] + shear * c[i] * c[j];
      ku[n++] = cross * b[i] * c[j] + shear * c[i] * b[j];
    }
    for (int j = i; j < 3; ++j) {  // row y_i, from its diagonal on
      if (j > i) ku[n++] = cross * c[i] * b[j] + shear * b[i] * c[j];
      ku[n++] = normal * c[i] * c[j] + shear * b[i] * b[j];
    }
  }
}

void cst_stiffness_factor(const double xy[6], const double d[9], double t, double w[18]) {
  double b[3], c[3];
  const double area = cst_gradients(xy, b, c);
  // Cholesky of the 3x3 D (lower triangular L, row-major).
  double l[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  l[0] = std::sqrt(d[0]);
  l[3] = d[3] / l[0];
  l[6] = d[6] / l[0];
  l[4] = std::sqrt(d[4] - l[3] * l[3]);
  l[7] = (d[7] - l[6] * l[3]) / l[4];
  l[8] = std::sqrt(d[8] - l[6] * l[6] - l[7] * l[7]);
  // Row a of W: sqrt(t / (4 |A|)) times row a of Bhat^T (as in cst_stiffness) times L.
  const double scale = std::sqrt(t / (4.0 * std::fabs(area)));
  for (int i = 0; i < 3; ++i) {
    const double rows[2][3] = {{b[i], 0.0, c[i]}, {0.0, c[i], b[i]}};
    for (int r = 0; r < 2; ++r)
      for (int j = 0; j < 3; ++j)
        w[3 * (2 * i + r) + j] =
            scale * (rows[r][0] * l[j] + rows[r][1] * l[3 + j] + rows[r][2] * l[6 + j]);
  }
}

void cst_strain(const double xy[6], const double u[6], double eps[3]) {
  double b[3], c[3];
  const double inv2a = 0.5 / cst_gradients(xy, b, c);
  eps[0] = inv2a * (b[0] * u[0] + b[1] * u[2] + b[2] * u[4]);
  eps[1] = inv2a * (c[0] * u[1] + c[1] * u[3] + c[2] * u[5]);
  eps[2] =
      inv2a * (c[0] * u[0] + b[0] * u[1] + c[1] * u[2] + b[1] * u[3] + c[2] * u[4] + b[2] * u[5]);
}

void cst_stress(const double d[9], const double eps[3], double sig[3]) {
  sig[0] = d[0] * eps[0] + d[1] * eps[1] + d[2] * eps[2];
  sig[1] = d[3] * eps[0] + d[4] * eps[1] + d[5] * eps[2];
  sig[2] = d[6] * eps[0] + d[7] * eps[1] + d[8] * eps[2];
}

void cst_internal_force(const double xy[6], const double sig[3], double t, double f[6]) {
  double b[3], c[3];
  const double area = cst_gradients(xy, b, c);
  // t |A| B^T sig = t |A| / (2A) Bhat^T sig.
  const double half_t = std::copysign(0.5 * t, area);
  for (int i = 0; i < 3; ++i) {
    f[2 * i] = half_t * (b[i] * sig[0] + c[i] * sig[2]);
    f[2 * i + 1] = half_t * (c[i] * sig[1] + b[i] * sig[2]);
  }
}

double cst_lumped_mass(double area, double density, double t) {
  return density * t * area / 3.0;
}

void cst_consistent_mass(double area, double density, double t, double m[36]) {
  const double off = density * t * area / 12.0;
  const double diag = 2.0 * off;
  for (int a = 0; a < 6; ++a) {
    for (int b = 0; b < 6; ++b) {
      const bool same_direction = (a & 1) == (b & 1);
      m[6 * a + b] = same_direction ? (a == b ? diag : off) : 0.0;
    }
  }
}

double out_of_plane_strain(const double eps[3], double poisson, PlaneKind plane) {
  return plane == PlaneKind::stress ? -poisson / (1.0 - poisson) * (eps[0] + eps[1]) : 0.0;
}

double out_of_plane_stress(const double sig[3], double poisson, PlaneKind plane) {
  return plane == PlaneKind::strain ? poisson * (sig[0] + sig[1]) : 0.0;
}

}  // namespace rockdd::kernels
