// Elastic damage laws (paper eqs. 2-8, tension positive) against their closed forms.
#include "kernels/damage_law.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

namespace k = rockdd::kernels;
using k::DamageLaw;
using k::PlaneKind;
using k::TensionOnset;

constexpr double kE0 = 30e9, kNu = 0.25, kFt = 3e6, kFc = 60e6, kPhi = M_PI / 6;
constexpr double kLambda = 0.1, kEta = 5.0;

k::DamageParams params(TensionOnset onset = TensionOnset::stress, double nu = kNu) {
  k::DamageParams p;
  p.young = kE0;
  p.poisson = nu;
  p.ft0 = kFt;
  p.fc0 = kFc;
  p.mohr_coulomb = k::mohr_coulomb_factor(kPhi);
  p.lambda = kLambda;
  p.eta = kEta;
  p.onset = onset;
  return p;
}

// Relative comparison with an absolute fallback for exact zeros.
void expect_rel(double got, double want, double tol) {
  if (want == 0.0) {
    EXPECT_EQ(got, 0.0);
  } else {
    EXPECT_NEAR(got, want, tol * std::fabs(want));
  }
}

// Plane-strain Hooke's law: in-plane strain of the stress {sxx, syy, 0} (eps_zz = 0).
void plane_strain_strain(double sxx, double syy, double nu, double eps[3]) {
  eps[0] = ((1 - nu * nu) * sxx - nu * (1 + nu) * syy) / kE0;
  eps[1] = ((1 - nu * nu) * syy - nu * (1 + nu) * sxx) / kE0;
  eps[2] = 0.0;
}

// One plane-stress element under a uniaxial stress along x, strain-controlled: eps = {e, -nu e,
// 0}, sig = {E e, 0, 0} with E = (1 - w) E0. At each strain the damage is re-evaluated with
// the updated modulus until it stops changing, as the engine's damage iteration does.
struct Point {
  double w, sigma;
  DamageLaw law;
};
Point uniaxial_point(double e, double w_old, const k::DamageParams& p) {
  const double eps[3] = {e, -p.poisson * e, 0.0};
  double w = w_old;
  DamageLaw law = DamageLaw::none;
  for (int it = 0; it < 50; ++it) {
    const double sig[3] = {(1.0 - w) * p.young * e, 0.0, 0.0};
    const k::DamageUpdate r = k::evaluate_damage(eps, sig, p, PlaneKind::stress, w);
    law = r.law;
    if (r.w == w) break;
    w = r.w;
  }
  return {w, (1.0 - w) * p.young * e, law};
}

TEST(DamageLaw, UniaxialTensionFollowsEq3) {
  // Eq. (2)+(3): sigma = (1 - w) E0 eps is E0 eps before eps_t0, the residual lambda ft0 on
  // the softening branch (w = 1 - lambda eps_t0/eps) and 0 from eta eps_t0 on (1e-10 rel).
  for (TensionOnset onset : {TensionOnset::stress, TensionOnset::strain}) {
    const k::DamageParams p = params(onset);
    const double et0 = kFt / kE0;
    int pre = 0, soft = 0, full = 0;
    double w = 0.0;
    for (int i = 1; i <= 400; ++i) {
      const double e = i * (1.3 * kEta * et0) / 400;
      const Point pt = uniaxial_point(e, w, p);
      w = pt.w;
      if (e < et0) {
        ++pre;
        EXPECT_EQ(pt.w, 0.0);
        EXPECT_EQ(pt.law, DamageLaw::none);
        expect_rel(pt.sigma, kE0 * e, 1e-10);
      } else if (e < kEta * et0) {
        ++soft;
        expect_rel(pt.w, 1.0 - kLambda * et0 / e, 1e-10);
        expect_rel(pt.sigma, kLambda * kFt, 1e-10);
        EXPECT_EQ(pt.law, DamageLaw::tension);
      } else {
        ++full;
        EXPECT_EQ(pt.w, 1.0);
        EXPECT_EQ(pt.sigma, 0.0);
        // The stiffness floor still carries 1e-6 E0 eps.
        expect_rel(k::damaged_modulus(kE0, pt.w) * e, 1e-6 * kE0 * e, 1e-12);
      }
    }
    EXPECT_GT(pre, 10);
    EXPECT_GT(soft, 10);
    EXPECT_GT(full, 10);
  }
}

TEST(DamageLaw, UniaxialCompressionFollowsEq7) {
  // Eq. (7) with eps_c0 = fc0/E0 (eq. 8 with no confinement): sigma = -E0 eps before the
  // peak, then w = 1 - lambda eps_c0/eps_c1 and sigma = -lambda fc0 (1e-10 rel). Stress onset:
  // the lateral expansion (eps_bar = sqrt(2) nu eps) must not trigger tension.
  const k::DamageParams p = params();
  const double ec0 = kFc / kE0;
  int pre = 0, soft = 0;
  double w = 0.0;
  for (int i = 1; i <= 300; ++i) {
    const double e = i * (4.0 * ec0) / 300;
    const double eps[3] = {-e, kNu * e, 0.0};
    DamageLaw law = DamageLaw::none;
    for (int it = 0; it < 50; ++it) {
      const double sig[3] = {-(1.0 - w) * kE0 * e, 0.0, 0.0};
      const k::DamageUpdate r = k::evaluate_damage(eps, sig, p, PlaneKind::stress, w);
      law = r.law;
      if (r.w == w) break;
      w = r.w;
    }
    const double sigma = -(1.0 - w) * kE0 * e;
    if (e < ec0) {
      ++pre;
      EXPECT_EQ(w, 0.0);
      EXPECT_EQ(law, DamageLaw::none);
      expect_rel(sigma, -kE0 * e, 1e-10);
    } else {
      ++soft;
      EXPECT_EQ(law, DamageLaw::shear);
      expect_rel(w, 1.0 - kLambda * ec0 / e, 1e-10);
      expect_rel(sigma, -kLambda * kFc, 1e-10);
    }
  }
  EXPECT_GT(pre, 10);
  EXPECT_GT(soft, 10);
}

TEST(DamageLaw, TensileDamageBranchesOfEq3) {
  // Eq. (3) translated: 0 below eps_t0, exactly 1 - lambda at eps_t0, 1 at eta eps_t0.
  const double et0 = 1e-4;
  EXPECT_EQ(k::tensile_damage(0.0, et0, kLambda, kEta), 0.0);
  EXPECT_EQ(k::tensile_damage(et0 * (1 - 1e-12), et0, kLambda, kEta), 0.0);
  EXPECT_DOUBLE_EQ(k::tensile_damage(et0, et0, kLambda, kEta), 1.0 - kLambda);
  EXPECT_DOUBLE_EQ(k::tensile_damage(2 * et0, et0, kLambda, kEta), 1.0 - kLambda / 2);
  EXPECT_NEAR(k::tensile_damage(kEta * et0 * (1 - 1e-12), et0, kLambda, kEta), 1.0 - kLambda / kEta,
              1e-10);
  EXPECT_EQ(k::tensile_damage(kEta * et0, et0, kLambda, kEta), 1.0);
}

TEST(DamageLaw, CrackBandEtaDissipatesTheFractureEnergyOverTheBandWidth) {
  // Bazant-Oh with eq. (3): the work per unit volume to break an element, the integral of
  // sigma = (1 - w) E0 eps from 0 to eta eps_t0, times its band width h must equal G_f. The
  // integral is taken numerically (midpoint rule, 2e6 intervals, 1e-4 relative) over the law
  // itself, so a wrong closed form in crack_band_ultimate_strain fails here.
  const double gf = 5.0;
  for (double h : {1e-4, 1e-3, 5e-3}) {
    for (double lambda : {0.05, 0.1, 1.0}) {
      const double eta = k::crack_band_ultimate_strain(gf, h, kFt, kE0, lambda);
      const double et0 = kFt / kE0, end = eta * et0;
      const int n = 2000000;
      double work = 0.0;
      for (int i = 0; i < n; ++i) {
        const double e = (i + 0.5) * end / n;
        work += (1.0 - k::tensile_damage(e, et0, lambda, eta)) * kE0 * e * end / n;
      }
      SCOPED_TRACE("h = " + std::to_string(h) + ", lambda = " + std::to_string(lambda));
      EXPECT_GT(eta, 1.0);
      expect_rel(work * h, gf, 1e-4);
    }
  }
  // At the limit width 2 E0 G_f / ft0^2 the element breaks at onset (eta = 1); wider ones
  // would need eta < 1 (the element's own snap-back).
  const double limit = k::crack_band_max_width(gf, kFt, kE0);
  EXPECT_DOUBLE_EQ(limit, 2 * kE0 * gf / (kFt * kFt));
  EXPECT_NEAR(k::crack_band_ultimate_strain(gf, limit, kFt, kE0, kLambda), 1.0, 1e-12);
  EXPECT_LT(k::crack_band_ultimate_strain(gf, 1.01 * limit, kFt, kE0, kLambda), 1.0);
  // sqrt(2 A): a right isosceles triangle of legs a is a wide.
  EXPECT_DOUBLE_EQ(k::crack_band_width(0.5 * 0.02 * 0.02), 0.02);
}

TEST(DamageLaw, CompressiveDamageBranchesOfEq7) {
  // Eq. (7): 0 below eps_c0, 1 - lambda eps_c0/eps_c1 from it, no ultimate strain.
  const double ec0 = 2e-3;
  EXPECT_EQ(k::compressive_damage(ec0 * (1 - 1e-12), ec0, kLambda), 0.0);
  EXPECT_DOUBLE_EQ(k::compressive_damage(ec0, ec0, kLambda), 1.0 - kLambda);
  EXPECT_DOUBLE_EQ(k::compressive_damage(10 * ec0, ec0, kLambda), 1.0 - kLambda / 10);
  EXPECT_EQ(k::compressive_damage(1e-3, -1e-4, kLambda), 1.0);
}

TEST(DamageLaw, MohrCoulombOnsetIsExactOnTheThreshold) {
  // Eq. (6), compression positive: c1 >= fc0 + k c3, k = (1 + sin phi)/(1 - sin phi). On the
  // threshold it fires; 1e-10 below it does not; 1e-10 above it does.
  for (double phi : {0.0, 20 * M_PI / 180, kPhi, M_PI / 4}) {
    const double kf = k::mohr_coulomb_factor(phi);
    EXPECT_NEAR(kf, (1 + std::sin(phi)) / (1 - std::sin(phi)), 1e-15 * kf);
    for (double c3 : {0.0, 1e6, 5e6, -1e6}) {
      const double q = kFc + kf * c3;
      EXPECT_TRUE(k::mohr_coulomb_onset(q, c3, kFc, kf));
      EXPECT_FALSE(k::mohr_coulomb_onset(q * (1 - 1e-10), c3, kFc, kf));
      EXPECT_TRUE(k::mohr_coulomb_onset(q * (1 + 1e-10), c3, kFc, kf));
    }
  }
}

// evaluate_damage on the stress {-q, syy, 0} at q = q_star (1 +- 1e-10): below it leaves the
// element intact, above it fires shear with the peak damage 1 - lambda (eps_c1 = eps_c0).
void expect_shear_threshold(double q_star, double syy, PlaneKind plane) {
  const k::DamageParams p = params();
  for (double f : {1 - 1e-10, 1 + 1e-10}) {
    const double q = q_star * f;
    const double sig[3] = {-q, syy, 0.0};
    double eps[3];
    if (plane == PlaneKind::strain) {
      plane_strain_strain(-q, syy, kNu, eps);
    } else {
      eps[0] = (-q - kNu * syy) / kE0;
      eps[1] = (syy + kNu * q) / kE0;
      eps[2] = 0.0;
    }
    const k::DamageUpdate r = k::evaluate_damage(eps, sig, p, plane, 0.0);
    if (f < 1) {
      EXPECT_EQ(r.law, DamageLaw::none) << "q* = " << q_star;
      EXPECT_EQ(r.w, 0.0);
    } else {
      EXPECT_EQ(r.law, DamageLaw::shear) << "q* = " << q_star;
      EXPECT_NEAR(r.w, 1.0 - kLambda, 1e-8);
    }
  }
}

TEST(DamageLaw, MohrCoulombThresholdThroughTheElementEvaluation) {
  const double kf = k::mohr_coulomb_factor(kPhi);
  // Plane strain, confinement p along y: s_zz = -nu (q + p) is less compressive than q and
  // more than p, so c1 = q, c3 = p and q* = fc0 + k p.
  const double p = 2e6;
  ASSERT_LT(p, kNu * (kFc + kf * p + p));
  expect_shear_threshold(kFc + kf * p, -p, PlaneKind::strain);
  // Plane stress with a lateral tension t < ft0: c3 = -t, q* = fc0 - k t.
  const double t = 1e6;
  expect_shear_threshold(kFc - kf * t, t, PlaneKind::stress);
  // Plane stress biaxial compression: the free face gives c3 = s_zz = 0, so q* = fc0 whatever
  // the in-plane confinement (documented choice: 3D principal stresses).
  expect_shear_threshold(kFc, -5e6, PlaneKind::stress);
  // Uniaxial compression: q* = fc0 (eq. 6 with c3 = 0), in both plane kinds' strain.
  expect_shear_threshold(kFc, 0.0, PlaneKind::stress);
}

TEST(DamageLaw, Eq8IsHookesLawAtThePeak) {
  // Eq. (8) (Hooke form): at a stress state on the Mohr-Coulomb surface, eps_c0 equals the
  // major compressive strain of that state, so the compressive law starts at w = 1 - lambda.
  // Uniaxial: eps_c0 = fc0/E0. (1e-12 relative.)
  const double kf = k::mohr_coulomb_factor(kPhi);
  for (double p : {0.0, 1e6, 4e6}) {
    const double q = kFc + kf * p;
    const double sig[3] = {-q, -p, 0.0};
    double eps[3], c[3];
    plane_strain_strain(-q, -p, kNu, eps);
    k::compressive_principal_stresses(sig, kNu, PlaneKind::strain, c);
    EXPECT_NEAR(c[0], q, 1e-15 * q);
    EXPECT_NEAR(c[2], p, 1e-9);
    const double ec0 = k::compressive_threshold_strain(c, kFc, kf, kE0, kNu);
    const double ec1 = k::major_compressive_strain(eps, kNu, PlaneKind::strain);
    expect_rel(ec0, ec1, 1e-12);
  }
  const double c_uni[3] = {kFc, 0.0, 0.0};
  expect_rel(k::compressive_threshold_strain(c_uni, kFc, kf, kE0, kNu), kFc / kE0, 1e-15);
}

TEST(DamageLaw, CompressiveStrengthFromCohesionIsTangentToTheCoulombLine) {
  // fc0 = 2 c cos phi/(1 - sin phi): the uniaxial Mohr circle (centre = radius = fc0/2)
  // touches tau = c + sigma tan phi, i.e. radius = centre sin phi + c cos phi (1e-12 rel).
  const double coh = 10e6;
  for (double phi : {0.0, 20 * M_PI / 180, kPhi, 50 * M_PI / 180}) {
    const double fc = k::compressive_strength(coh, phi);
    expect_rel(fc / 2, fc / 2 * std::sin(phi) + coh * std::cos(phi), 1e-12);
  }
  expect_rel(k::compressive_strength(coh, 0.0), 2 * coh, 1e-15);
}

TEST(DamageLaw, DamageNeverDecreases) {
  // w_new = max(w_old, w_law): unloading, reversal to compression and a lower re-load keep w.
  const k::DamageParams p = params();
  const double et0 = kFt / kE0;
  const Point loaded = uniaxial_point(3 * et0, 0.0, p);
  expect_rel(loaded.w, 1.0 - kLambda / 3, 1e-12);
  for (double e : {2 * et0, 0.5 * et0, 0.0, -0.5 * et0, -1e-3}) {
    const double eps[3] = {e, -kNu * e, 0.0};
    const double sig[3] = {k::damaged_modulus(kE0, loaded.w) * e, 0.0, 0.0};
    EXPECT_EQ(k::evaluate_damage(eps, sig, p, PlaneKind::stress, loaded.w).w, loaded.w);
  }
  // Re-loading past the old maximum resumes the softening branch of eq. (3).
  expect_rel(uniaxial_point(4 * et0, loaded.w, p).w, 1.0 - kLambda / 4, 1e-12);
  // A fully damaged element stays at 1, with nothing to fire.
  const double eps[3] = {1e-2, 0, 0}, sig[3] = {1.0, 0, 0};
  const k::DamageUpdate full = k::evaluate_damage(eps, sig, p, PlaneKind::stress, 1.0);
  EXPECT_EQ(full.w, 1.0);
  EXPECT_EQ(full.law, DamageLaw::none);
}

TEST(DamageLaw, OutOfPlaneStrainInEquivalentStrain) {
  // Eq. (4)-(5) translated: eps_bar = sqrt(sum <eps_i>^2) over e1, e2 and eps_zz, with
  // eps_zz = 0 (plane strain) or -nu/(1-nu)(exx + eyy) (plane stress). 1e-15 relative.
  // In-plane biaxial compression: plane stress swells out of plane, plane strain does not.
  const double comp[3] = {-3e-4, -1e-4, 0.0};
  expect_rel(k::equivalent_tensile_strain(comp, kNu, PlaneKind::stress), kNu / (1 - kNu) * 4e-4,
             1e-15);
  EXPECT_EQ(k::equivalent_tensile_strain(comp, kNu, PlaneKind::strain), 0.0);
  // Biaxial tension: eps_zz < 0 in plane stress, so both give sqrt(e1^2 + e2^2).
  const double ten[3] = {1e-4, 2e-4, 0.0};
  expect_rel(k::equivalent_tensile_strain(ten, kNu, PlaneKind::stress), std::sqrt(5e-8), 1e-15);
  expect_rel(k::equivalent_tensile_strain(ten, kNu, PlaneKind::strain), std::sqrt(5e-8), 1e-15);
  // Pure shear gxy = 2e-4: principal strains +-1e-4, eps_zz = 0 in both: eps_bar = 1e-4.
  const double shear[3] = {0.0, 0.0, 2e-4};
  for (PlaneKind plane : {PlaneKind::stress, PlaneKind::strain}) {
    expect_rel(k::equivalent_tensile_strain(shear, kNu, plane), 1e-4, 1e-15);
  }
  // Uniaxial compression eps = {-e, nu e, 0} in plane stress: eps_zz = nu e as well.
  const double uni[3] = {-1e-3, kNu * 1e-3, 0.0};
  expect_rel(k::equivalent_tensile_strain(uni, kNu, PlaneKind::stress), std::sqrt(2.0) * kNu * 1e-3,
             1e-15);
  expect_rel(k::equivalent_tensile_strain(uni, kNu, PlaneKind::strain), kNu * 1e-3, 1e-15);
}

TEST(DamageLaw, StrainOnsetFiresAtFtOverE0InUniaxialTension) {
  // "strain" onset: eps_bar >= eps_t0 = ft0/E0; in plane-stress uniaxial tension eps_bar = exx,
  // so it fires exactly at exx = ft0/E0 (w = 1 - lambda) and not 1e-10 below.
  const k::DamageParams p = params(TensionOnset::strain);
  const double et0 = kFt / kE0;
  for (double f : {1.0, 1 - 1e-10}) {
    const double e = et0 * f;
    const double eps[3] = {e, -kNu * e, 0.0};
    const double sig[3] = {kE0 * e, 0.0, 0.0};
    const k::DamageUpdate r = k::evaluate_damage(eps, sig, p, PlaneKind::stress, 0.0);
    EXPECT_EQ(r.law, f == 1.0 ? DamageLaw::tension : DamageLaw::none);
    EXPECT_DOUBLE_EQ(r.w, f == 1.0 ? 1.0 - kLambda : 0.0);
  }
}

TEST(DamageLaw, StressOnsetFiresAtFtInUniaxialTension) {
  // "stress" onset: s1 >= ft0 exactly at sxx = ft0, not 1e-10 below.
  const k::DamageParams p = params(TensionOnset::stress);
  for (double f : {1.0, 1 - 1e-10}) {
    const double s = kFt * f;
    const double eps[3] = {s / kE0, -kNu * s / kE0, 0.0};
    const double sig[3] = {s, 0.0, 0.0};
    const k::DamageUpdate r = k::evaluate_damage(eps, sig, p, PlaneKind::stress, 0.0);
    EXPECT_EQ(r.law, f == 1.0 ? DamageLaw::tension : DamageLaw::none);
  }
}

TEST(DamageLaw, StrainOnsetFiresEarlierInABrazilianStressState) {
  // METHOD.md: with s2 = -3 s1 (disk centre, plane stress) e1 = (1 + 3 nu) s1/E0, so the strain
  // onset fires at s1 = ft0/(1 + 3 nu) while the stress onset waits for s1 = ft0.
  const double s = kFt / (1 + 3 * kNu) * (1 + 1e-10);
  const double sig[3] = {s, -3 * s, 0.0};
  const double eps[3] = {(s + 3 * kNu * s) / kE0, (-3 * s - kNu * s) / kE0, 0.0};
  EXPECT_EQ(k::evaluate_damage(eps, sig, params(TensionOnset::strain), PlaneKind::stress, 0.0).law,
            DamageLaw::tension);
  EXPECT_EQ(k::evaluate_damage(eps, sig, params(TensionOnset::stress), PlaneKind::stress, 0.0).law,
            DamageLaw::none);
}

TEST(DamageLaw, StressOnsetBelowTheStrainThresholdGivesPeakDamage) {
  // Equal biaxial tension s1 = s2 = ft0 in plane stress with nu = 0.3: eps_bar =
  // sqrt(2) (1 - nu) ft0/E0 = 0.99 eps_t0 < eps_t0, yet the stress onset has fired: the element
  // is at its peak and takes w = 1 - lambda (eq. 3 at eps_t0), not 0.
  const double nu = 0.3;
  const double e = (1 - nu) * kFt / kE0;
  const double eps[3] = {e, e, 0.0}, sig[3] = {kFt, kFt, 0.0};
  ASSERT_LT(k::equivalent_tensile_strain(eps, nu, PlaneKind::stress), kFt / kE0);
  const k::DamageUpdate r =
      k::evaluate_damage(eps, sig, params(TensionOnset::stress, nu), PlaneKind::stress, 0.0);
  EXPECT_EQ(r.law, DamageLaw::tension);
  EXPECT_DOUBLE_EQ(r.w, 1.0 - kLambda);
}

TEST(DamageLaw, TensionIsCheckedBeforeShear) {
  // Tension cut-off: a state past both criteria (s1 > ft0, c1 > fc0 + k c3) is tension.
  const double sig[3] = {1.5 * kFt, -2 * kFc, 0.0};
  const double eps[3] = {(sig[0] - kNu * sig[1]) / kE0, (sig[1] - kNu * sig[0]) / kE0, 0.0};
  double c[3];
  k::compressive_principal_stresses(sig, kNu, PlaneKind::stress, c);
  ASSERT_TRUE(k::mohr_coulomb_onset(c[0], c[2], kFc, k::mohr_coulomb_factor(kPhi)));
  EXPECT_EQ(k::evaluate_damage(eps, sig, params(), PlaneKind::stress, 0.0).law, DamageLaw::tension);
}

TEST(DamageLaw, CompressivePrincipalStressesAreOrdered) {
  // c = -s over {s1, s2, s_zz}: plane strain s_zz = nu (sxx + syy), plane stress 0; c1>=c2>=c3.
  const double sig[3] = {-10e6, 4e6, 3e6};  // s1,2 = -3e6 +- sqrt(49e12 + 9e12)
  const double r = std::sqrt(58e12);
  double c[3];
  k::compressive_principal_stresses(sig, kNu, PlaneKind::stress, c);
  expect_rel(c[0], 3e6 + r, 1e-15);
  EXPECT_EQ(c[1], 0.0);
  expect_rel(c[2], 3e6 - r, 1e-15);
  k::compressive_principal_stresses(sig, kNu, PlaneKind::strain, c);
  expect_rel(c[0], 3e6 + r, 1e-15);
  expect_rel(c[1], 1.5e6, 1e-15);  // -nu (sxx + syy) = 0.25 * 6e6
  expect_rel(c[2], 3e6 - r, 1e-15);
}

TEST(DamageLaw, EffectiveModulusHasAFloor) {
  // Eq. (2) with the floor: max((1 - w) E0, floor E0).
  EXPECT_EQ(k::damaged_modulus(kE0, 0.0), kE0);
  EXPECT_DOUBLE_EQ(k::damaged_modulus(kE0, 0.75), 0.25 * kE0);
  EXPECT_DOUBLE_EQ(k::damaged_modulus(kE0, 1.0), 1e-6 * kE0);
  EXPECT_DOUBLE_EQ(k::damaged_modulus(kE0, 1.0, 1e-3), 1e-3 * kE0);
  EXPECT_DOUBLE_EQ(k::damaged_modulus(kE0, 0.9999999), 1e-6 * kE0);
}

TEST(DamageLaw, DissipationIsTheElasticEnergyTheModulusDropReleases) {
  // At fixed strain, 1/2 (E(w_old) - E(w_new)) eps.D1 eps with D1 the unit-modulus matrix.
  // Uniaxial stress in plane stress, eps = {e, -nu e, 0}: eps.D1 eps = e^2, so the release is
  // 1/2 (w_new - w_old) E0 e^2 to round-off; down to the floor it stops at 1 - 1e-6 of E0.
  const double e = 1.5e-4;
  const double eps[3] = {e, -kNu * e, 0.0};
  expect_rel(k::damage_dissipation(eps, kE0, kNu, PlaneKind::stress, 0.0, 0.9),
             0.5 * 0.9 * kE0 * e * e, 1e-13);
  expect_rel(k::damage_dissipation(eps, kE0, kNu, PlaneKind::stress, 0.5, 1.0),
             0.5 * (0.5 - 1e-6) * kE0 * e * e, 1e-13);
  EXPECT_EQ(k::damage_dissipation(eps, kE0, kNu, PlaneKind::stress, 0.3, 0.3), 0.0);
  // Pure shear gamma in plane strain: eps.D1 eps = gamma^2 / (2 (1 + nu)) (G = E / 2(1+nu)).
  const double gamma = 2e-4;
  const double shear[3] = {0.0, 0.0, gamma};
  expect_rel(k::damage_dissipation(shear, kE0, kNu, PlaneKind::strain, 0.0, 0.5),
             0.5 * 0.5 * kE0 * gamma * gamma / (2.0 * (1.0 + kNu)), 1e-13);
}

}  // namespace

TEST(DamageLaw, OnsetRatioIsOneExactlyWhereALawFires) {
  // onset_ratio orders damage events: max(s1 / ft0, (c1 - k c3) / fc0) on the effective stress
  // sigma / (1 - w). Closed forms: uniaxial tension s gives s / ft0; uniaxial compression q
  // gives q / fc0 (c3 = 0 in plane stress); pure shear tau gives max(tau / ft0,
  // (tau + k tau) / fc0). The ratio crosses 1 where evaluate_damage starts damage (1e-12).
  const k::DamageParams p = params();
  const double kf = k::mohr_coulomb_factor(kPhi);
  for (double s : {0.5 * kFt, kFt, 1.7 * kFt}) {
    const double sig[3] = {s, 0.0, 0.0}, eps[3] = {s / kE0, -kNu * s / kE0, 0.0};
    expect_rel(k::onset_ratio(eps, sig, p, PlaneKind::stress, 0.0), s / kFt, 1e-12);
    // A damaged element is judged on its effective stress.
    expect_rel(k::onset_ratio(eps, sig, p, PlaneKind::stress, 0.5), 2 * s / kFt, 1e-12);
  }
  for (double q : {0.3 * kFc, kFc, 1.2 * kFc}) {
    const double sig[3] = {0.0, -q, 0.0}, eps[3] = {kNu * q / kE0, -q / kE0, 0.0};
    expect_rel(k::onset_ratio(eps, sig, p, PlaneKind::stress, 0.0), std::max(0.0, q / kFc), 1e-12);
  }
  const double tau = 2e6;
  const double sig[3] = {0.0, 0.0, tau};
  const double eps[3] = {0.0, 0.0, 2 * (1 + kNu) * tau / kE0};
  expect_rel(k::onset_ratio(eps, sig, p, PlaneKind::stress, 0.0),
             std::max(tau / kFt, (1 + kf) * tau / kFc), 1e-12);
  // Strain onset: eps_bar / eps_t0, with eps_bar = eps1 for uniaxial tension in plane stress.
  const k::DamageParams ps = params(TensionOnset::strain);
  const double s = 0.8 * kFt;
  const double st[3] = {s, 0.0, 0.0}, et[3] = {s / kE0, -kNu * s / kE0, 0.0};
  expect_rel(k::onset_ratio(et, st, ps, PlaneKind::stress, 0.0),
             k::equivalent_tensile_strain(et, kNu, PlaneKind::stress) / (kFt / kE0), 1e-12);
  // Laws that are off give 0.
  k::DamageParams off = params();
  off.ft0 = 0.0;
  off.fc0 = 0.0;
  EXPECT_EQ(k::onset_ratio(et, st, off, PlaneKind::stress, 0.0), 0.0);
  // Consistency with the laws: just below 1 no law fires, just above one does.
  for (double f : {1 - 1e-9, 1 + 1e-9}) {
    const double sg[3] = {f * kFt, 0.0, 0.0}, eg[3] = {f * kFt / kE0, -kNu * f * kFt / kE0, 0.0};
    const bool fires = k::evaluate_damage(eg, sg, p, PlaneKind::stress, 0.0).w > 0.0;
    EXPECT_EQ(fires, k::onset_ratio(eg, sg, p, PlaneKind::stress, 0.0) >= 1.0);
  }
}
