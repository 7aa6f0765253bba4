#include "kernels/corotated_cst_batch.hpp"

#include <cmath>

namespace rockdd::kernels {

namespace {

constexpr int B = kCstBatch;

// Each statement below repeats the one-element kernel's expression, operand for operand: a
// reordered sum or a factor taken out would round differently.

/// cst_gradients of each lane's reference corners: b, c and the signed area.
void reference_gradients(const CstBatch& batch, double b[3][B], double c[3][B], double area[B]) {
  const auto& xy0 = batch.xy0;
  for (int i = 0; i < B; ++i) {
    b[0][i] = xy0[3][i] - xy0[5][i];
    b[1][i] = xy0[5][i] - xy0[1][i];
    b[2][i] = xy0[1][i] - xy0[3][i];
    c[0][i] = xy0[4][i] - xy0[2][i];
    c[1][i] = xy0[0][i] - xy0[4][i];
    c[2][i] = xy0[2][i] - xy0[0][i];
    area[i] = 0.5 * (b[1][i] * c[2][i] - b[2][i] * c[1][i]);
  }
}

/// corotation.cpp's unnormalised_rotation of each lane: (p, q) = sign(A) (F11 + F22,
/// F21 - F12) 2|A|.
void unnormalised_rotation(const CstBatch& batch, const double b[3][B], const double c[3][B],
                           const double area[B], double p[B], double q[B]) {
  const auto& x = batch.x;
  for (int i = 0; i < B; ++i) {
    double f11 = 0.0, f12 = 0.0, f21 = 0.0, f22 = 0.0;
    for (int k = 0; k < 3; ++k) {
      f11 += x[2 * k][i] * b[k][i];
      f12 += x[2 * k][i] * c[k][i];
      f21 += x[2 * k + 1][i] * b[k][i];
      f22 += x[2 * k + 1][i] * c[k][i];
    }
    const double sign = 2.0 * area[i] < 0.0 ? -1.0 : 1.0;
    p[i] = sign * (f11 + f22);
    q[i] = sign * (f21 - f12);
  }
}

/// Lanes [count, B) take lane 0's corners, so that every lane computes finite numbers.
void pad_corners(CstBatch& batch, int count) {
  for (int i = count; i < B; ++i)
    for (int k = 0; k < 6; ++k) {
      batch.xy0[k][i] = batch.xy0[k][0];
      batch.x[k][i] = batch.x[k][0];
    }
}

}  // namespace

void turned_within(CstBatch& batch, int count, const double frame_cos[kCstBatch],
                   const double frame_sin[kCstBatch], double bound, bool within[kCstBatch]) {
  pad_corners(batch, count);  // the moduli are not read (nor set by the frame check)
  double b[3][B], c[3][B], area[B], p[B], q[B];
  reference_gradients(batch, b, c, area);
  unnormalised_rotation(batch, b, c, area, p, q);
  // As corotation.cpp's turned_within.
  for (int i = 0; i < B; ++i) {
    const double along = p[i] * frame_cos[i] + q[i] * frame_sin[i];
    const double across = q[i] * frame_cos[i] - p[i] * frame_sin[i];
    within[i] = along > 0.0 && std::abs(across) < 0.5 * bound * along;
  }
}

void corotated_cst_forces(CstBatch& batch, int count, PlaneKind plane, double t) {
  pad_corners(batch, count);
  for (int i = count; i < B; ++i) {
    batch.young[i] = batch.young[0];
    batch.poisson[i] = batch.poisson[0];
  }
  const auto& xy0 = batch.xy0;
  const auto& x = batch.x;
  double b[3][B], c[3][B], area[B], p[B], q[B];
  reference_gradients(batch, b, c, area);
  unnormalised_rotation(batch, b, c, area, p, q);

  // element_rotation_factor: (p, q) normalised, or the identity where it has no length.
  // Divided in every lane and chosen after, in a loop of its own: a division used on one side
  // of a choice only would be moved into a branch, which keeps the loop from vectorizing.
  double norm[B], along[B], across[B];
  for (int i = 0; i < B; ++i) {
    norm[i] = std::sqrt(p[i] * p[i] + q[i] * q[i]);
    along[i] = p[i] / norm[i];
    across[i] = q[i] / norm[i];
  }
  double cs[B], sn[B];
  for (int i = 0; i < B; ++i) {
    const bool turned = norm[i] > 0.0;
    cs[i] = turned ? along[i] : 1.0;
    sn[i] = turned ? across[i] : 0.0;
  }

  // corotated_displacement: the corners about their centroid, turned back, less the
  // reference corners about theirs.
  double u[6][B];
  for (int i = 0; i < B; ++i) {
    const double xc = (x[0][i] + x[2][i] + x[4][i]) / 3.0;
    const double yc = (x[1][i] + x[3][i] + x[5][i]) / 3.0;
    const double x0c = (xy0[0][i] + xy0[2][i] + xy0[4][i]) / 3.0;
    const double y0c = (xy0[1][i] + xy0[3][i] + xy0[5][i]) / 3.0;
    for (int k = 0; k < 3; ++k) {
      const double dx = x[2 * k][i] - xc, dy = x[2 * k + 1][i] - yc;
      u[2 * k][i] = cs[i] * dx + sn[i] * dy - (xy0[2 * k][i] - x0c);
      u[2 * k + 1][i] = -sn[i] * dx + cs[i] * dy - (xy0[2 * k + 1][i] - y0c);
    }
  }

  // isotropic_moduli (elasticity_matrix's D: normal, cross, 0 / cross, normal, 0 / 0, 0, shear).
  double normal[B], cross[B], shear[B];
  for (int i = 0; i < B; ++i) {
    const double young = batch.young[i], nu = batch.poisson[i];
    shear[i] = young / (2.0 * (1.0 + nu));
    if (plane == PlaneKind::stress) {
      const double f = young / (1.0 - nu * nu);
      normal[i] = f;
      cross[i] = f * nu;
    } else {
      const double f = young / ((1.0 + nu) * (1.0 - 2.0 * nu));
      normal[i] = f * (1.0 - nu);
      cross[i] = f * nu;
    }
  }

  // cst_strain and cst_stress in the element's frame (D's zeros multiplied as cst_stress does:
  // 0 x eps is -0, or NaN, where eps is, and the sums keep that).
  double eps[3][B], sig[3][B];
  for (int i = 0; i < B; ++i) {
    const double inv2a = 0.5 / area[i];
    eps[0][i] = inv2a * (b[0][i] * u[0][i] + b[1][i] * u[2][i] + b[2][i] * u[4][i]);
    eps[1][i] = inv2a * (c[0][i] * u[1][i] + c[1][i] * u[3][i] + c[2][i] * u[5][i]);
    eps[2][i] = inv2a * (c[0][i] * u[0][i] + b[0][i] * u[1][i] + c[1][i] * u[2][i] +
                         b[1][i] * u[3][i] + c[2][i] * u[4][i] + b[2][i] * u[5][i]);
    sig[0][i] = normal[i] * eps[0][i] + cross[i] * eps[1][i] + 0.0 * eps[2][i];
    sig[1][i] = cross[i] * eps[0][i] + normal[i] * eps[1][i] + 0.0 * eps[2][i];
    sig[2][i] = 0.0 * eps[0][i] + 0.0 * eps[1][i] + shear[i] * eps[2][i];
  }

  // cst_internal_force, then rotate_nodal.
  for (int i = 0; i < B; ++i) {
    const double half_t = std::copysign(0.5 * t, area[i]);
    for (int k = 0; k < 3; ++k) {
      const double fx = half_t * (b[k][i] * sig[0][i] + c[k][i] * sig[2][i]);
      const double fy = half_t * (c[k][i] * sig[1][i] + b[k][i] * sig[2][i]);
      batch.force[2 * k][i] = cs[i] * fx - sn[i] * fy;
      batch.force[2 * k + 1][i] = sn[i] * fx + cs[i] * fy;
    }
  }

  // rotate_tensor of the stress, and of the strain with its tensor shear (half the
  // engineering one).
  for (int i = 0; i < B; ++i) {
    const double c_ = cs[i], s_ = sn[i];
    {
      const double xx = sig[0][i], yy = sig[1][i], xy = sig[2][i];
      batch.stress[0][i] = c_ * c_ * xx - 2.0 * c_ * s_ * xy + s_ * s_ * yy;
      batch.stress[1][i] = s_ * s_ * xx + 2.0 * c_ * s_ * xy + c_ * c_ * yy;
      batch.stress[2][i] = c_ * s_ * (xx - yy) + (c_ * c_ - s_ * s_) * xy;
    }
    {
      const double xx = eps[0][i], yy = eps[1][i], xy = eps[2][i] * 0.5;
      batch.strain[0][i] = c_ * c_ * xx - 2.0 * c_ * s_ * xy + s_ * s_ * yy;
      batch.strain[1][i] = s_ * s_ * xx + 2.0 * c_ * s_ * xy + c_ * c_ * yy;
      batch.strain[2][i] = (c_ * s_ * (xx - yy) + (c_ * c_ - s_ * s_) * xy) * 2.0;
    }
  }
}

}  // namespace rockdd::kernels
