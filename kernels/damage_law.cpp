#include "kernels/damage_law.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "kernels/principal.hpp"

namespace rockdd::kernels {

double equivalent_tensile_strain(const double eps[3], double poisson, PlaneKind plane) {
  double e1, e2;
  principal_strains(eps, e1, e2);
  const double ez = out_of_plane_strain(eps, poisson, plane);
  // Macaulay brackets: only the tensile principal strains open cracks.
  const double a = std::max(e1, 0.0), b = std::max(e2, 0.0), c = std::max(ez, 0.0);
  return std::sqrt(a * a + b * b + c * c);
}

double tensile_damage(double eps_bar, double eps_t0, double lambda, double eta) {
  if (eps_bar < eps_t0) return 0.0;
  if (eps_bar >= eta * eps_t0) return 1.0;
  // Softening plateau: (1 - w) E0 eps_bar = lambda E0 eps_t0 = lambda ft0, the residual.
  return 1.0 - lambda * eps_t0 / eps_bar;
}

double crack_band_width(double area) {
  return std::sqrt(2.0 * area);
}

double crack_band_ultimate_strain(double gf, double h, double ft0, double young, double lambda) {
  const double eps_t0 = ft0 / young;
  return 1.0 + (gf / (h * ft0 * eps_t0) - 0.5) / lambda;
}

double crack_band_max_width(double gf, double ft0, double young) {
  return 2.0 * young * gf / (ft0 * ft0);
}

bool tensile_onset(TensionOnset mode, double s1, double eps_bar, double ft0, double young) {
  return mode == TensionOnset::stress ? s1 >= ft0 : eps_bar >= ft0 / young;
}

double mohr_coulomb_factor(double phi) {
  const double s = std::sin(phi);
  return (1.0 + s) / (1.0 - s);
}

double compressive_strength(double cohesion, double phi) {
  return 2.0 * cohesion * std::cos(phi) / (1.0 - std::sin(phi));
}

namespace {
/// The compressive principal stresses c[0] >= c[1] >= c[2] from the in-plane principal
/// stresses s1 >= s2 (tension positive) and the out-of-plane stress of `sig`.
void order_compressive(double s1, double s2, const double sig[3], double poisson, PlaneKind plane,
                       double c[3]) {
  // Compression positive reverses the order: the most tensile stress becomes c3.
  c[0] = -s2;
  c[1] = -s1;
  c[2] = -out_of_plane_stress(sig, poisson, plane);
  if (c[2] > c[1]) std::swap(c[1], c[2]);
  if (c[1] > c[0]) std::swap(c[0], c[1]);
}
}  // namespace

void compressive_principal_stresses(const double sig[3], double poisson, PlaneKind plane,
                                    double c[3]) {
  double s1, s2;
  principal_values(sig[0], sig[1], sig[2], s1, s2);
  order_compressive(s1, s2, sig, poisson, plane, c);
}

bool mohr_coulomb_onset(double c1, double c3, double fc0, double k) {
  // Written as c1 >= fc0 + k c3 (not c1 - k c3 >= fc0) so a caller that builds c1 from the
  // same expression sits exactly on the threshold.
  return c1 >= fc0 + k * c3;
}

double compressive_threshold_strain(const double c[3], double fc0, double k, double young,
                                    double poisson) {
  // The paper prints -mu (sigma1 + sigma2); Hooke's law along the major compressive axis at the
  // peak c1 = fc0 + k c3 needs the two other stresses, -nu (c2 + c3), and only this form
  // gives eps_c0 = fc0 / E0 in uniaxial compression, as f_cr = lambda E0 eps_c0 requires.
  return (fc0 + k * c[2] - poisson * (c[1] + c[2])) / young;
}

double major_compressive_strain(const double eps[3], double poisson, PlaneKind plane) {
  double e1, e2;
  principal_strains(eps, e1, e2);
  return -std::min(e2, out_of_plane_strain(eps, poisson, plane));
}

double compressive_damage(double eps_c1, double eps_c0, double lambda) {
  if (eps_c1 < eps_c0) return 0.0;
  if (eps_c0 <= 0.0) return 1.0;
  // Residual plateau, as in tension: (1 - w) E0 eps_c1 = lambda fc0.
  return 1.0 - lambda * eps_c0 / eps_c1;
}

double damage_dissipation(const double eps[3], double young, double poisson, PlaneKind plane,
                          double w_old, double w_new, double floor) {
  double d[9];
  elasticity_matrix(1.0, poisson, plane, d);  // per unit modulus
  double energy = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) energy += eps[i] * d[3 * i + j] * eps[j];
  return 0.5 * energy *
         (damaged_modulus(young, w_old, floor) - damaged_modulus(young, w_new, floor));
}

double onset_ratio(const double eps[3], const double sig[3], const DamageParams& p, PlaneKind plane,
                   double w_old) {
  const double scale = 1.0 / std::max(1.0 - w_old, p.floor);
  const double se[3] = {sig[0] * scale, sig[1] * scale, sig[2] * scale};
  // One set of principal stresses serves both laws (this runs on every element and pass).
  double s1, s2;
  principal_values(se[0], se[1], se[2], s1, s2);
  double ratio = 0.0;
  if (p.ft0 > 0.0)
    ratio = p.onset == TensionOnset::stress
                ? s1 / p.ft0
                : equivalent_tensile_strain(eps, p.poisson, plane) / (p.ft0 / p.young);
  if (p.fc0 > 0.0) {
    double c[3];
    order_compressive(s1, s2, se, p.poisson, plane, c);
    ratio = std::max(ratio, (c[0] - p.mohr_coulomb * c[2]) / p.fc0);
  }
  return ratio;
}

DamageUpdate evaluate_damage(const double eps[3], const double sig[3], const DamageParams& p,
                             PlaneKind plane, double w_old) {
  if (w_old >= 1.0) return {w_old, DamageLaw::none};  // nothing left to lose

  // Effective stress (stress on the intact ligaments): the damaged element is checked against
  // its undamaged strengths, which is what lets the strain laws carry on past onset.
  const double scale = 1.0 / std::max(1.0 - w_old, p.floor);
  const double se[3] = {sig[0] * scale, sig[1] * scale, sig[2] * scale};

  const double eps_bar = equivalent_tensile_strain(eps, p.poisson, plane);
  const double eps_t0 = p.ft0 / p.young;
  double s1, s2;
  principal_values(se[0], se[1], se[2], s1, s2);
  // A law whose strength is not given (<= 0) is off.
  if (p.ft0 > 0.0 && tensile_onset(p.onset, s1, eps_bar, p.ft0, p.young)) {
    // A stress onset can fire with eps_bar a little below eps_t0 (e.g. biaxial tension):
    // the element is at its peak, so it gets the peak damage 1 - lambda.
    const double w = tensile_damage(std::max(eps_bar, eps_t0), eps_t0, p.lambda, p.eta);
    return {std::max(w_old, w), DamageLaw::tension};
  }

  double c[3];
  order_compressive(s1, s2, se, p.poisson, plane, c);
  if (p.fc0 > 0.0 && mohr_coulomb_onset(c[0], c[2], p.fc0, p.mohr_coulomb)) {
    const double eps_c0 =
        compressive_threshold_strain(c, p.fc0, p.mohr_coulomb, p.young, p.poisson);
    const double eps_c1 = major_compressive_strain(eps, p.poisson, plane);
    const double w = compressive_damage(std::max(eps_c1, eps_c0), eps_c0, p.lambda);
    return {std::max(w_old, w), DamageLaw::shear};
  }
  return {w_old, DamageLaw::none};
}

}  // namespace rockdd::kernels
