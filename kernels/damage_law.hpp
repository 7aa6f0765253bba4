#pragma once
// Elastic damage laws of one element (paper eqs. 2-8): pure functions, no state.
//
// Conventions, shared by every caller:
//  - Tension positive everywhere (strain eps[3] = {exx, eyy, gxy}, stress sig[3] = {sxx, syy,
//    sxy}), as in cst.hpp. The paper writes its laws with compression positive; here they are
//    translated, not copied: eps_bar >= 0 is built from the tensile principal strains, and the
//    Mohr-Coulomb check works on compressive principal stresses c = -s (positive in
//    compression), c1 >= c2 >= c3.
//  - Principal values are three-dimensional: the in-plane pair plus the out-of-plane value
//    (cst.hpp: eps_zz = 0 and s_zz = nu (sxx + syy) in plane strain; eps_zz = -nu/(1-nu)
//    (exx + eyy) and s_zz = 0 in plane stress). Mohr-Coulomb uses the largest and smallest of
//    the three compressive stresses, so in plane stress a biaxially compressed element gets
//    c3 = 0 from its free face (no spurious confinement), and in plane strain the
//    out-of-plane stress confines when it is the smallest.
//  - The tensile stress onset uses the in-plane s1: s_zz never exceeds it when s1 > 0
//    (s_zz = nu (s1 + s2) <= 2 nu s1 < s1), and is <= 0 otherwise.

#include "kernels/cst.hpp"

namespace rockdd::kernels {

/// The law that fired in an evaluation (tension is checked first; shear only without it).
enum class DamageLaw { none, tension, shear };

/// Undamaged properties and strengths of one element (after heterogeneity draws).
struct DamageParams {
  double young = 0;         // E0 (Pa), undamaged modulus
  double poisson = 0;       // nu, unchanged by damage
  double ft0 = 0;           // uniaxial tensile strength (Pa, > 0)
  double fc0 = 0;           // uniaxial compressive strength (Pa, > 0); see compressive_strength()
  double mohr_coulomb = 1;  // k = mohr_coulomb_factor(phi), phi the internal friction angle
  double lambda = 0.1;      // residual strength coefficient: f_r = lambda f_0 (0 < lambda <= 1)
  double eta = 5.0;         // ultimate tensile strain coefficient: eps_tu = eta eps_t0 (eta > 1)
  TensionOnset onset = TensionOnset::stress;
  double floor = kStiffnessFloor;  // stiffness floor, as a fraction of E0
};

/// Result of one evaluation: the new (never smaller) damage and the law whose criterion held.
struct DamageUpdate {
  double w = 0;
  DamageLaw law = DamageLaw::none;
};

/// Equivalent tensile strain sqrt(sum <eps_i>^2), <x> = max(x, 0), over the two in-plane
/// principal strains and eps_zz (paper eq. 4-5, translated to tension positive).
double equivalent_tensile_strain(const double eps[3], double poisson, PlaneKind plane);

/// Tensile damage, paper eq. (3): 0 for eps_bar < eps_t0, 1 - lambda eps_t0 / eps_bar for
/// eps_t0 <= eps_bar < eta eps_t0, 1 beyond. Requires eps_t0 > 0.
double tensile_damage(double eps_bar, double eps_t0, double lambda, double eta);

/// Crack-band width of a linear triangle: sqrt(2 A), the leg of the right isosceles triangle
/// of the same area (the usual choice for constant-strain triangles, e.g. Rots 1988). It is
/// the width of a band one element wide, per unit length of crack, to within the mesh's
/// orientation to the crack.
double crack_band_width(double area);

/// Bazant-Oh crack band with the paper's tensile law (eq. 3): the ultimate strain coefficient
/// eta for which an element of band width h dissipates the fracture energy gf (J/m^2) per
/// unit crack area. Eq. (3) loads to ft0 at eps_t0, drops to the residual lambda ft0 and holds
/// it up to eta eps_t0, so the work per unit volume to break is
/// g = ft0 eps_t0 (1/2 + lambda (eta - 1)); setting g h = gf gives
/// eta = 1 + (gf / (h ft0 eps_t0) - 1/2) / lambda. A result below 1 means the element is too
/// large to dissipate only gf (h > 2 E0 gf / ft0^2, a snap-back of the element itself).
double crack_band_ultimate_strain(double gf, double h, double ft0, double young, double lambda);

/// Largest crack-band width for which crack_band_ultimate_strain is >= 1: 2 E0 gf / ft0^2.
double crack_band_max_width(double gf, double ft0, double young);

/// Tensile onset: s1 >= ft0 ("stress") or eps_bar >= ft0 / E0 ("strain").
bool tensile_onset(TensionOnset mode, double s1, double eps_bar, double ft0, double young);

/// Mohr-Coulomb factor k = (1 + sin phi) / (1 - sin phi).
double mohr_coulomb_factor(double phi);

/// Uniaxial compressive strength from cohesion: fc0 = 2 c cos phi / (1 - sin phi).
double compressive_strength(double cohesion, double phi);

/// Principal stresses positive in compression, c[0] >= c[1] >= c[2], from the in-plane
/// stress and the out-of-plane stress of the plane kind.
void compressive_principal_stresses(const double sig[3], double poisson, PlaneKind plane,
                                    double c[3]);

/// Mohr-Coulomb onset, paper eq. (6) with compression positive: c1 >= fc0 + k c3.
bool mohr_coulomb_onset(double c1, double c3, double fc0, double k);

/// Compressive threshold strain, paper eq. (8) as Hooke's law at the Mohr-Coulomb peak
/// c1 = fc0 + k c3: eps_c0 = (fc0 + k c3 - nu (c2 + c3)) / E0, c = compressive principals.
double compressive_threshold_strain(const double c[3], double fc0, double k, double young,
                                    double poisson);

/// Major compressive principal strain, positive in compression: -min(e2, eps_zz).
double major_compressive_strain(const double eps[3], double poisson, PlaneKind plane);

/// Compressive damage, paper eq. (7): 0 for eps_c1 < eps_c0, else 1 - lambda eps_c0 / eps_c1
/// (1 if eps_c0 <= 0: the Mohr-Coulomb peak was reached with no compressive reserve).
double compressive_damage(double eps_c1, double eps_c0, double lambda);

/// Energy released per unit volume (J/m^3) as damage grows from w_old to w_new at strain eps:
/// the fall of the elastic energy 1/2 eps.D eps when the modulus drops from E(w_old) to
/// E(w_new) at fixed strain. A secant damage law unloads to the origin, so this energy does
/// not come back: it is dissipated.
double damage_dissipation(const double eps[3], double young, double poisson, PlaneKind plane,
                          double w_old, double w_new, double floor = kStiffnessFloor);

/// How far an undamaged element stands past its onset: the larger of the tensile ratio (s1 / ft0
/// for a stress onset, eps_bar / eps_t0 for a strain onset) and the Mohr-Coulomb ratio
/// (c1 - k c3) / fc0, on the effective stress as in evaluate_damage. A law fires exactly when
/// its ratio is >= 1; laws that are off (strength <= 0) give 0. Used to order damage events:
/// the most overstressed elements fail first.
double onset_ratio(const double eps[3], const double sig[3], const DamageParams& p, PlaneKind plane,
                   double w_old);

/// New damage of an element: max(w_old, w_law), w_law from the first criterion that holds
/// (tension, then Mohr-Coulomb). sig is the element's stress under its current (damaged)
/// modulus; the criteria use the effective stress sig / max(1 - w_old, floor), so a softening
/// element keeps following the strain laws when loaded past its previous maximum. On onset
/// the strain is taken at least at the threshold, so a fired law gives w >= 1 - lambda.
/// law != none does not by itself mean growth (an unloaded softening element still meets its
/// criterion): "newly damaged" is w > w_old. A fully damaged element (w_old >= 1) returns none.
/// A law whose strength is not positive (ft0 or fc0 <= 0) is off.
DamageUpdate evaluate_damage(const double eps[3], const double sig[3], const DamageParams& p,
                             PlaneKind plane, double w_old);

}  // namespace rockdd::kernels
