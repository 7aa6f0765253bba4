// Constant-strain triangle kernels against hand derivations and FE identities.
#include "kernels/cst.hpp"

#include "kernels/corotation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace {

using rockdd::kernels::PlaneKind;
namespace k = rockdd::kernels;

using Mat6 = Eigen::Matrix<double, 6, 6, Eigen::RowMajor>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

constexpr std::array<PlaneKind, 2> kPlanes = {PlaneKind::stress, PlaneKind::strain};

Mat6 stiffness(const double xy[6], double young, double poisson, PlaneKind plane, double t) {
  double d[9];
  k::elasticity_matrix(young, poisson, plane, d);
  Mat6 km;
  k::cst_stiffness(xy, d, t, km.data());
  return km;
}

Mat3 elasticity(double young, double poisson, PlaneKind plane) {
  Mat3 d;
  k::elasticity_matrix(young, poisson, plane, d.data());
  return d;
}

// A counter-clockwise triangle of size about 1, centred within [-5, 5]^2, with every angle
// above 15 degrees so that its stiffness is well conditioned.
std::array<double, 6> random_triangle(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), centre(-5.0, 5.0);
  for (;;) {
    std::array<double, 6> xy;
    const double cx = centre(rng), cy = centre(rng);
    for (int i = 0; i < 3; ++i) {
      xy[2 * i] = cx + unit(rng);
      xy[2 * i + 1] = cy + unit(rng);
    }
    double min_angle = M_PI;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, m = (i + 2) % 3;
      const double ax = xy[2 * j] - xy[2 * i], ay = xy[2 * j + 1] - xy[2 * i + 1];
      const double bx = xy[2 * m] - xy[2 * i], by = xy[2 * m + 1] - xy[2 * i + 1];
      min_angle = std::min(
          min_angle,
          std::acos((ax * bx + ay * by) / std::sqrt((ax * ax + ay * ay) * (bx * bx + by * by))));
    }
    if (min_angle < 15.0 * M_PI / 180.0) continue;
    if (k::cst_signed_area(xy.data()) < 0.0) {
      std::swap(xy[2], xy[4]);
      std::swap(xy[3], xy[5]);
    }
    return xy;
  }
}

TEST(CstGeometry, SignedAreaAndGradientsOfTheUnitRightTriangle) {
  // (0,0),(1,0),(0,1): A = 1/2; b_i = y_j - y_m = {-1, 1, 0}, c_i = x_m - x_j = {-1, 0, 1}.
  const double xy[6] = {0, 0, 1, 0, 0, 1};
  const double cw[6] = {0, 0, 0, 1, 1, 0};
  double b[3], c[3];
  EXPECT_EQ(k::cst_signed_area(xy), 0.5);
  EXPECT_EQ(k::cst_signed_area(cw), -0.5);
  EXPECT_EQ(k::cst_gradients(xy, b, c), 0.5);
  EXPECT_EQ(b[0], -1.0);
  EXPECT_EQ(b[1], 1.0);
  EXPECT_EQ(b[2], 0.0);
  EXPECT_EQ(c[0], -1.0);
  EXPECT_EQ(c[1], 0.0);
  EXPECT_EQ(c[2], 1.0);
}

TEST(CstGeometry, GradientsReproduceLinearFunctionsOnRandomTriangles) {
  // For w = alpha + beta x + gamma y: sum_i b_i w_i / (2A) = beta, sum_i c_i w_i / (2A) = gamma,
  // and sum b_i = sum c_i = 0 (constants have no gradient). Tolerance 1e-13 absolute, O(1) data.
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const auto xy = random_triangle(rng);
    double b[3], c[3];
    const double area = k::cst_gradients(xy.data(), b, c);
    EXPECT_NEAR(area, k::cst_signed_area(xy.data()), 1e-13);
    const double alpha = 0.3, beta = -1.7, gamma = 2.2;
    double db = 0, dc = 0;
    for (int i = 0; i < 3; ++i) {
      const double w = alpha + beta * xy[2 * i] + gamma * xy[2 * i + 1];
      db += b[i] * w;
      dc += c[i] * w;
    }
    EXPECT_NEAR(db / (2 * area), beta, 1e-13);
    EXPECT_NEAR(dc / (2 * area), gamma, 1e-13);
    EXPECT_NEAR(b[0] + b[1] + b[2], 0.0, 1e-13);
    EXPECT_NEAR(c[0] + c[1] + c[2], 0.0, 1e-13);
  }
}

// Hand derivation for (0,0),(1,0),(0,1), t = 1, D = [d11 d12 0; d12 d11 0; 0 0 g]:
//   Bhat = 2A B has rows  exx: [-1  0  1  0  0  0]
//                         eyy: [ 0 -1  0  0  0  1]
//                         gxy: [-1 -1  0  1  1  0]
//   k = t A B^T D B = t / (4A) Bhat^T D Bhat = 1/2 Bhat^T D Bhat, which, written out, is
//   1/2 * [ d11+g  d12+g  -d11  -g  -g  -d12 ]
//         [ d12+g  d11+g  -d12  -g  -g  -d11 ]
//         [ -d11   -d12    d11   0   0   d12 ]
//         [ -g     -g      0     g   g   0   ]
//         [ -g     -g      0     g   g   0   ]
//         [ -d12   -d11    d12   0   0   d11 ]
// E = 1, nu = 0 (both modes): d11 = 1, d12 = 0, g = 1/2                 -> 4 k below.
// E = 1, nu = 0.25, plane stress: E/(1-nu^2) = 16/15, d11 = 16/15,
//   d12 = 4/15, g = E/(2(1+nu)) = 2/5                                   -> 30 k below.
// E = 1, nu = 0.25, plane strain: E/((1+nu)(1-2nu)) = 8/5, d11 = 6/5,
//   d12 = 2/5, g = 2/5                                                  -> 5 k below.
struct HandStiffness {
  double poisson;
  PlaneKind plane;
  double divisor;
  double times_divisor[36];
};

constexpr HandStiffness kHandCases[] = {
    {0.0, PlaneKind::stress, 4.0, {3,  1,  -2, -1, -1, 0, 1,  3,  0, -1, -1, -2,
                                   -2, 0,  2,  0,  0,  0, -1, -1, 0, 1,  1,  0,
                                   -1, -1, 0,  1,  1,  0, 0,  -2, 0, 0,  0,  2}},
    {0.0, PlaneKind::strain, 4.0, {3,  1,  -2, -1, -1, 0, 1,  3,  0, -1, -1, -2,
                                   -2, 0,  2,  0,  0,  0, -1, -1, 0, 1,  1,  0,
                                   -1, -1, 0,  1,  1,  0, 0,  -2, 0, 0,  0,  2}},
    {0.25, PlaneKind::stress, 30.0, {22,  10, -16, -6, -6, -4, 10, 22,  -4, -6, -6, -16,
                                     -16, -4, 16,  0,  0,  4,  -6, -6,  0,  6,  6,  0,
                                     -6,  -6, 0,   6,  6,  0,  -4, -16, 4,  0,  0,  16}},
    {0.25, PlaneKind::strain, 5.0, {4,  2,  -3, -1, -1, -1, 2,  4,  -1, -1, -1, -3,
                                    -3, -1, 3,  0,  0,  1,  -1, -1, 0,  1,  1,  0,
                                    -1, -1, 0,  1,  1,  0,  -1, -3, 1,  0,  0,  3}},
};

TEST(CstStiffness, MatchesHandDerivationForTheUnitRightTriangle) {
  // Entries are O(1): compared to 1e-14 absolute.
  const double xy[6] = {0, 0, 1, 0, 0, 1};
  for (const auto& hand : kHandCases) {
    const Mat6 km = stiffness(xy, 1.0, hand.poisson, hand.plane, 1.0);
    for (int i = 0; i < 36; ++i)
      EXPECT_NEAR(km.data()[i], hand.times_divisor[i] / hand.divisor, 1e-14)
          << "nu " << hand.poisson << " plane " << static_cast<int>(hand.plane) << " entry " << i;
  }
}

TEST(CstStiffness, ScalesWithThicknessAndIgnoresNodeOrientation) {
  // k(t) = t k(1); a clockwise listing (nodes 1 and 2 swapped) gives the permuted matrix and
  // the permuted internal force. Tolerance 1e-14 relative to max |k| (and to max |sig| for f,
  // the triangle being of size about 1).
  std::mt19937_64 rng(5);
  const auto xy = random_triangle(rng);
  const Mat6 k1 = stiffness(xy.data(), 2.0, 0.3, PlaneKind::stress, 1.0);
  const Mat6 k3 = stiffness(xy.data(), 2.0, 0.3, PlaneKind::stress, 3.0);
  const double scale = k1.cwiseAbs().maxCoeff();
  EXPECT_LE((k3 - 3.0 * k1).cwiseAbs().maxCoeff(), 1e-14 * 3.0 * scale);

  const double cw[6] = {xy[0], xy[1], xy[4], xy[5], xy[2], xy[3]};
  ASSERT_LT(k::cst_signed_area(cw), 0.0);
  const Mat6 kcw = stiffness(cw, 2.0, 0.3, PlaneKind::stress, 1.0);
  const int perm[6] = {0, 1, 4, 5, 2, 3};
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) EXPECT_NEAR(kcw(a, b), k1(perm[a], perm[b]), 1e-14 * scale);

  // The same holds for the nodal internal force of a given stress.
  const double sig[3] = {2.0, -1.0, 0.5};
  double f[6], fcw[6];
  k::cst_internal_force(xy.data(), sig, 1.0, f);
  k::cst_internal_force(cw, sig, 1.0, fcw);
  for (int a = 0; a < 6; ++a) EXPECT_NEAR(fcw[a], f[perm[a]], 1e-14 * 2.0);
}

TEST(CstStiffness, RigidBodyModesGiveNoStrainAndNoForce) {
  // Modes: u = (1, 0), u = (0, 1), u = (-y, x). Checks: |eps| <= 1e-12 ||u||_inf / h with
  // h = sqrt(|A|), and ||k u||_inf <= 1e-12 ||k||_inf ||u||_inf.
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const auto xy = random_triangle(rng);
    const double h = std::sqrt(std::fabs(k::cst_signed_area(xy.data())));
    for (PlaneKind plane : kPlanes) {
      const Mat6 km = stiffness(xy.data(), 3e10, 0.27, plane, 0.8);
      const double knorm = km.cwiseAbs().rowwise().sum().maxCoeff();
      for (int mode = 0; mode < 3; ++mode) {
        Vec6 u;
        for (int i = 0; i < 3; ++i) {
          const double x = xy[2 * i], y = xy[2 * i + 1];
          u[2 * i] = mode == 0 ? 1.0 : mode == 1 ? 0.0 : -y;
          u[2 * i + 1] = mode == 0 ? 0.0 : mode == 1 ? 1.0 : x;
        }
        const double unorm = u.cwiseAbs().maxCoeff();
        double eps[3];
        k::cst_strain(xy.data(), u.data(), eps);
        for (double e : eps) EXPECT_LE(std::fabs(e), 1e-12 * unorm / h) << "mode " << mode;
        EXPECT_LE((km * u).cwiseAbs().maxCoeff(), 1e-12 * knorm * unorm) << "mode " << mode;
      }
    }
  }
}

TEST(CstStiffness, SymmetricPositiveSemiDefiniteWithThreeZeroEigenvalues) {
  // Exact symmetry (k is mirrored); eigenvalues: three with |lambda| <= 1e-12 lambda_max
  // (the rigid modes), three >= 1e-6 lambda_max (the three strain modes).
  std::mt19937_64 rng(13);
  for (int trial = 0; trial < 20; ++trial) {
    const auto xy = random_triangle(rng);
    for (PlaneKind plane : kPlanes) {
      for (double nu : {0.0, 0.25, 0.3}) {
        const Mat6 km = stiffness(xy.data(), 1e9, nu, plane, 1.0);
        EXPECT_TRUE(km == km.transpose());
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> solver(km);
        const auto lambda = solver.eigenvalues();  // ascending
        const double lmax = lambda[5];
        ASSERT_GT(lmax, 0.0);
        for (int i = 0; i < 3; ++i) EXPECT_LE(std::fabs(lambda[i]), 1e-12 * lmax);
        for (int i = 3; i < 6; ++i) EXPECT_GE(lambda[i], 1e-6 * lmax);
      }
    }
  }
}

TEST(CstPatch, ConstantStrainFieldIsReproducedAroundAnInteriorNode) {
  // Five boundary nodes (irregular, counter-clockwise) around one interior node, five
  // elements (b_k, b_k+1, interior). Boundary gets u = a + G x; the interior node solved from
  // K_ii u_i = -K_ib u_b must equal a + G x_i, and every element strain must equal
  // {G00, G11, G01 + G10}; tolerance 1e-12 relative to max |u_b| and to max |eps|.
  const double nodes[6][2] = {{0.0, 0.0}, {1.2, -0.1}, {1.5, 0.9},
                              {0.6, 1.4}, {-0.2, 0.8}, {0.55, 0.47}};
  const int interior = 5;
  const double a[2] = {1e-3, -2e-3};
  const double g[2][2] = {{2e-4, -3e-4}, {5e-4, -1e-4}};
  const double expected_eps[3] = {g[0][0], g[1][1], g[0][1] + g[1][0]};
  const double eps_scale = 5e-4 + 2e-4;
  auto field = [&](const double* x, double* u) {
    for (int r = 0; r < 2; ++r) u[r] = a[r] + g[r][0] * x[0] + g[r][1] * x[1];
  };

  for (PlaneKind plane : kPlanes) {
    Eigen::MatrixXd kglobal = Eigen::MatrixXd::Zero(12, 12);
    std::array<std::array<double, 6>, 5> elements;
    std::array<std::array<int, 3>, 5> conn;
    for (int e = 0; e < 5; ++e) {
      conn[e] = {e, (e + 1) % 5, interior};
      for (int i = 0; i < 3; ++i) {
        elements[e][2 * i] = nodes[conn[e][i]][0];
        elements[e][2 * i + 1] = nodes[conn[e][i]][1];
      }
      ASSERT_GT(k::cst_signed_area(elements[e].data()), 0.0);
      const Mat6 ke = stiffness(elements[e].data(), 2e10, 0.3, plane, 0.5);
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
          kglobal(2 * conn[e][i / 2] + i % 2, 2 * conn[e][j / 2] + j % 2) += ke(i, j);
    }
    Eigen::VectorXd u(12);
    for (int n = 0; n < 5; ++n) field(nodes[n], &u[2 * n]);
    const double u_scale = u.head(10).cwiseAbs().maxCoeff();
    const Eigen::Matrix2d kii = kglobal.block(10, 10, 2, 2);
    const Eigen::Vector2d rhs = -kglobal.block(10, 0, 2, 10) * u.head(10);
    u.tail(2) = kii.lu().solve(rhs);

    double exact[2];
    field(nodes[interior], exact);
    EXPECT_NEAR(u[10], exact[0], 1e-12 * u_scale);
    EXPECT_NEAR(u[11], exact[1], 1e-12 * u_scale);
    for (int e = 0; e < 5; ++e) {
      double ue[6], eps[3];
      for (int i = 0; i < 3; ++i) {
        ue[2 * i] = u[2 * conn[e][i]];
        ue[2 * i + 1] = u[2 * conn[e][i] + 1];
      }
      k::cst_strain(elements[e].data(), ue, eps);
      for (int r = 0; r < 3; ++r) EXPECT_NEAR(eps[r], expected_eps[r], 1e-12 * eps_scale);
    }
  }
}

TEST(CstElasticity, PlaneStrainOverPlaneStressRatiosFollowTheFormulas) {
  // With the same E and nu = 0.3:
  //   D_strain(0,0) / D_stress(0,0) = (1-nu)/((1+nu)(1-2nu)) * (1-nu^2) = (1-nu)^2 / (1-2nu)
  //   D_strain(0,1) / D_stress(0,1) = nu/((1+nu)(1-2nu)) * (1-nu^2)/nu = (1-nu) / (1-2nu)
  //   D_strain(2,2) / D_stress(2,2) = 1 (both are G = E / (2(1+nu)))
  // Tolerance 1e-14 relative.
  const double e = 7e9, nu = 0.3;
  const Mat3 ds = elasticity(e, nu, PlaneKind::stress);
  const Mat3 dn = elasticity(e, nu, PlaneKind::strain);
  const double r00 = (1 - nu) * (1 - nu) / (1 - 2 * nu);
  const double r01 = (1 - nu) / (1 - 2 * nu);
  EXPECT_NEAR(dn(0, 0) / ds(0, 0), r00, 1e-14 * r00);
  EXPECT_NEAR(dn(1, 1) / ds(1, 1), r00, 1e-14 * r00);
  EXPECT_NEAR(dn(0, 1) / ds(0, 1), r01, 1e-14 * r01);
  EXPECT_NEAR(dn(2, 2) / ds(2, 2), 1.0, 1e-14);
  EXPECT_NEAR(ds(2, 2), e / (2 * (1 + nu)), 1e-14 * e);
  EXPECT_NEAR(ds(0, 0), e / (1 - nu * nu), 1e-14 * e);
  EXPECT_NEAR(dn(0, 0), e * (1 - nu) / ((1 + nu) * (1 - 2 * nu)), 1e-14 * e);
  for (const Mat3& d : {ds, dn}) {
    EXPECT_TRUE(d == d.transpose());
    EXPECT_EQ(d(0, 2), 0.0);
    EXPECT_EQ(d(1, 2), 0.0);
  }
}

TEST(CstElasticity, UniaxialPlaneStressGivesHookesLaw) {
  // sig = {s, 0, 0} in plane stress: exx = s/E, eyy = -nu s/E, gxy = 0, and the
  // out-of-plane strain -nu/(1-nu)(exx+eyy) = -nu s/E; szz = 0. Tolerance 1e-14 relative.
  const double e = 5e10, nu = 0.2, s = 3e6;
  const Mat3 d = elasticity(e, nu, PlaneKind::stress);
  const Eigen::Vector3d eps = d.lu().solve(Eigen::Vector3d(s, 0, 0));
  const double scale = s / e;
  EXPECT_NEAR(eps[0], s / e, 1e-14 * scale);
  EXPECT_NEAR(eps[1], -nu * s / e, 1e-14 * scale);
  EXPECT_NEAR(eps[2], 0.0, 1e-14 * scale);
  EXPECT_NEAR(k::out_of_plane_strain(eps.data(), nu, PlaneKind::stress), -nu * s / e,
              1e-14 * scale);
  const double sig[3] = {s, 0, 0};
  EXPECT_EQ(k::out_of_plane_stress(sig, nu, PlaneKind::stress), 0.0);
}

// 3D isotropic Hooke's law, sigma = lambda tr(eps) I + 2 mu eps, for {exx, eyy, ezz, gxy}.
std::array<double, 4> hooke_3d(double e, double nu, const std::array<double, 4>& eps) {
  const double lambda = e * nu / ((1 + nu) * (1 - 2 * nu)), mu = e / (2 * (1 + nu));
  const double tr = eps[0] + eps[1] + eps[2];
  return {lambda * tr + 2 * mu * eps[0], lambda * tr + 2 * mu * eps[1],
          lambda * tr + 2 * mu * eps[2], mu * eps[3]};
}

TEST(CstElasticity, BothPlaneKindsAgreeWith3dHooke) {
  // Plane strain: ezz = 0, and 3D Hooke gives {sxx, syy, sxy} = D eps and szz = nu(sxx+syy).
  // Plane stress: with ezz = -nu/(1-nu)(exx+eyy), 3D Hooke gives szz = 0 and D eps in-plane.
  // Tolerance 1e-13 relative to max |sigma|.
  const double e = 2e10, nu = 0.3;
  const double eps[3] = {1.3e-4, -0.4e-4, 2.1e-4};
  for (PlaneKind plane : kPlanes) {
    double d[9], sig[3];
    k::elasticity_matrix(e, nu, plane, d);
    k::cst_stress(d, eps, sig);
    const double ezz = k::out_of_plane_strain(eps, nu, plane);
    if (plane == PlaneKind::strain) {
      EXPECT_EQ(ezz, 0.0);
    }
    const auto s3 = hooke_3d(e, nu, {eps[0], eps[1], ezz, eps[2]});
    const double scale = std::max({std::fabs(s3[0]), std::fabs(s3[1]), std::fabs(s3[3])});
    EXPECT_NEAR(sig[0], s3[0], 1e-13 * scale);
    EXPECT_NEAR(sig[1], s3[1], 1e-13 * scale);
    EXPECT_NEAR(sig[2], s3[3], 1e-13 * scale);
    EXPECT_NEAR(k::out_of_plane_stress(sig, nu, plane), s3[2], 1e-13 * scale);
  }
}

TEST(CstElasticity, NearlyIncompressiblePlaneStrainIsFinite) {
  // nu = 0.4999: D(0,0) = E(1-nu)/((1+nu)(1-2nu)) ~ 1667 E is finite and D positive
  // definite; the shear term stays G = E/(2(1+nu)) to 1e-14 relative (no 1-2nu cancellation).
  const double e = 1e9, nu = 0.4999;
  const Mat3 d = elasticity(e, nu, PlaneKind::strain);
  EXPECT_TRUE(d.allFinite());
  EXPECT_NEAR(d(0, 0), e * (1 - nu) / ((1 + nu) * (1 - 2 * nu)), 1e-11 * d(0, 0));
  EXPECT_NEAR(d(2, 2), e / (2 * (1 + nu)), 1e-14 * e);
  EXPECT_EQ(d.llt().info(), Eigen::Success);
}

TEST(CstIsotropicStiffness, UpperTriangleEqualsTheGeneralForm) {
  // cst_isotropic_stiffness_upper is cst_stiffness with D's zeros left out, so each entry
  // must agree to round-off: |dk| <= 1e-14 max|k|, for both planes, either node order
  // (|A| in the integral) and nu up to 0.4999 in plane strain.
  std::mt19937_64 rng(23);
  for (int trial = 0; trial < 50; ++trial) {
    auto xy = random_triangle(rng);
    if (trial % 2 == 1) {  // clockwise: swap nodes 1 and 2
      std::swap(xy[2], xy[4]);
      std::swap(xy[3], xy[5]);
    }
    for (PlaneKind plane : kPlanes)
      for (double nu : {0.0, 0.22, 0.4999}) {
        const Mat6 km = stiffness(xy.data(), 3e10, nu, plane, 0.7);
        double ku[k::kUpperEntries];
        k::cst_isotropic_stiffness_upper(xy.data(), k::isotropic_moduli(3e10, nu, plane), 0.7, ku);
        const double scale = km.cwiseAbs().maxCoeff();
        for (int a = 0, i = 0; a < 6; ++a)
          for (int b = a; b < 6; ++b, ++i)
            EXPECT_LE(std::abs(ku[i] - km(a, b)), 1e-14 * scale) << "entry " << a << "," << b;
      }
  }
}

TEST(CstInternalForce, EqualsStiffnessTimesDisplacement) {
  // f(u) = t A B^T D B u must equal k u: ||f - k u||_inf <= 1e-12 ||k||_inf ||u||_inf.
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const auto xy = random_triangle(rng);
    for (PlaneKind plane : kPlanes) {
      double d[9], eps[3], sig[3];
      k::elasticity_matrix(4e10, 0.22, plane, d);
      Mat6 km;
      k::cst_stiffness(xy.data(), d, 0.6, km.data());
      Vec6 u, f;
      for (int i = 0; i < 6; ++i) u[i] = 1e-3 * unit(rng);
      k::cst_strain(xy.data(), u.data(), eps);
      k::cst_stress(d, eps, sig);
      k::cst_internal_force(xy.data(), sig, 0.6, f.data());
      const double knorm = km.cwiseAbs().rowwise().sum().maxCoeff();
      EXPECT_LE((f - km * u).cwiseAbs().maxCoeff(), 1e-12 * knorm * u.cwiseAbs().maxCoeff());
    }
  }
}

TEST(CstInternalForce, NodalForcesAreInEquilibrium) {
  // For any constant stress: sum fx = sum fy = 0 and sum (x fy - y fx) = 0, tolerance
  // 1e-13 relative to max |f| (times max |x| for the moment).
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const auto xy = random_triangle(rng);
    const double sig[3] = {1e6 * unit(rng), 1e6 * unit(rng), 1e6 * unit(rng)};
    double f[6];
    k::cst_internal_force(xy.data(), sig, 1.0, f);
    double fx = 0, fy = 0, moment = 0, fmax = 0, xmax = 0;
    for (int i = 0; i < 3; ++i) {
      fx += f[2 * i];
      fy += f[2 * i + 1];
      moment += xy[2 * i] * f[2 * i + 1] - xy[2 * i + 1] * f[2 * i];
      fmax = std::max({fmax, std::fabs(f[2 * i]), std::fabs(f[2 * i + 1])});
      xmax = std::max({xmax, std::fabs(xy[2 * i]), std::fabs(xy[2 * i + 1])});
    }
    EXPECT_NEAR(fx, 0.0, 1e-13 * fmax);
    EXPECT_NEAR(fy, 0.0, 1e-13 * fmax);
    EXPECT_NEAR(moment, 0.0, 1e-13 * fmax * xmax);
  }
}

TEST(CstInternalForce, UniformTractionOnTheRightTriangle) {
  // (0,0),(1,0),(0,1), t = 1, sig = {s, 0, 0}: f = 1/2 Bhat^T sig, Bhat row exx = b = {-1,1,0}
  // and row gxy = {c0,b0,c1,b1,c2,b2}; so f = s/2 {-1, 0, 1, 0, 0, 0}, exactly.
  const double xy[6] = {0, 0, 1, 0, 0, 1};
  const double sig[3] = {4.0, 0.0, 0.0};
  double f[6];
  k::cst_internal_force(xy, sig, 1.0, f);
  const double expected[6] = {-2, 0, 2, 0, 0, 0};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(f[i], expected[i]);
}

TEST(CstMass, LumpedMassTotalsRhoTA) {
  // Three nodes of rho t A / 3 each sum to rho t A per direction; 1e-15 relative.
  const double area = 0.37, rho = 2600, t = 0.5;
  const double m = k::cst_lumped_mass(area, rho, t);
  EXPECT_NEAR(3 * m, rho * t * area, 1e-15 * rho * t * area);
}

TEST(CstMass, ConsistentMassTotalsRhoTAAndIsPositiveDefinite) {
  // Sum over the x-x block = rho t A (and y-y), x-y coupling zero, symmetric, and eigenvalues
  // rho t A / 12 * {1, 1, 4} per direction (those of [2 1 1; 1 2 1; 1 1 2]); 1e-14 relative.
  const double area = 0.37, rho = 2600, t = 0.5, total = rho * t * area;
  Mat6 m;
  k::cst_consistent_mass(area, rho, t, m.data());
  double sum_xx = 0, sum_yy = 0;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      if (a % 2 == 0 && b % 2 == 0) sum_xx += m(a, b);
      if (a % 2 == 1 && b % 2 == 1) sum_yy += m(a, b);
      if (a % 2 != b % 2) {
        EXPECT_EQ(m(a, b), 0.0);
      }
    }
  EXPECT_NEAR(sum_xx, total, 1e-14 * total);
  EXPECT_NEAR(sum_yy, total, 1e-14 * total);
  EXPECT_TRUE(m == m.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> solver(m);
  const double expected[6] = {1, 1, 1, 1, 4, 4};
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(solver.eigenvalues()[i], expected[i] * total / 12, 1e-14 * total);
}

// The stiffness factor reproduces k: W W^T = t A B^T D B (definition of W), for both node
// orders, both planes and nu up to 0.4999, to 1e-12 of the largest entry; turned by
// rotate_nodal on each column it reproduces rotate_element_matrix's T k T^T.
TEST(CstStiffnessFactor, ReproducesTheStiffnessInAnyFrame) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    std::array<double, 6> xy = random_triangle(rng);
    if (trial % 2 == 1) {  // clockwise: integrals over |A|
      std::swap(xy[2], xy[4]);
      std::swap(xy[3], xy[5]);
    }
    for (const PlaneKind plane : kPlanes)
      for (const double nu : {0.0, 0.2, 0.45, 0.4999}) {
        double d[9];
        k::elasticity_matrix(3.0e10, nu, plane, d);
        const Mat6 km = stiffness(xy.data(), 3.0e10, nu, plane, 0.7);
        Eigen::Matrix<double, 6, 3, Eigen::RowMajor> w;
        k::cst_stiffness_factor(xy.data(), d, 0.7, w.data());
        const double scale = km.cwiseAbs().maxCoeff();
        EXPECT_LT((w * w.transpose() - km).cwiseAbs().maxCoeff(), 1e-12 * scale);

        const double theta = 0.3 + trial;
        Mat6 turned = km;
        k::rotate_element_matrix(k::Rotation(theta), turned.data());
        Eigen::Matrix<double, 6, 3, Eigen::ColMajor> wt = w;
        for (int j = 0; j < 3; ++j) k::rotate_nodal(k::Rotation(theta), wt.col(j).data());
        EXPECT_LT((wt * wt.transpose() - turned).cwiseAbs().maxCoeff(), 1e-12 * scale);
      }
  }
}

}  // namespace
