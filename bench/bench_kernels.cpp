// Throughput of the CST kernels over a pre-built array of random triangles.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>
#include <vector>

#include "kernels/cst.hpp"
#include "kernels/damage_law.hpp"
#include "kernels/weibull.hpp"

namespace {

namespace k = rockdd::kernels;

constexpr int kElements = 100000;

// Counter-clockwise triangles of size about 1 (the kernels do not branch on shape).
const std::vector<double>& triangles() {
  static const std::vector<double> xy = [] {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), centre(0.0, 300.0);
    std::vector<double> out(6 * kElements);
    for (int e = 0; e < kElements; ++e) {
      double* t = &out[6 * e];
      do {
        const double cx = centre(rng), cy = centre(rng);
        for (int i = 0; i < 3; ++i) {
          t[2 * i] = cx + unit(rng);
          t[2 * i + 1] = cy + unit(rng);
        }
      } while (std::abs(k::cst_signed_area(t)) < 0.05);
      if (k::cst_signed_area(t) < 0.0) {
        std::swap(t[2], t[4]);
        std::swap(t[3], t[5]);
      }
    }
    return out;
  }();
  return xy;
}

const std::vector<double>& displacements() {
  static const std::vector<double> u = [] {
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> unit(-1e-3, 1e-3);
    std::vector<double> out(6 * kElements);
    for (double& v : out) v = unit(rng);
    return out;
  }();
  return u;
}

// One element stiffness per element with a shared D (homogeneous material).
void BM_CstStiffness(benchmark::State& state) {
  const auto& xy = triangles();
  double d[9], k36[36];
  k::elasticity_matrix(2e10, 0.25, k::PlaneKind::strain, d);
  for (auto _ : state) {
    for (int e = 0; e < kElements; ++e) {
      k::cst_stiffness(&xy[6 * e], d, 1.0, k36);
      benchmark::DoNotOptimize(k36);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kElements);
}
BENCHMARK(BM_CstStiffness)->Unit(benchmark::kMillisecond);

// As the engine assembles: D rebuilt per element (damaged modulus), then k.
void BM_ElasticityAndStiffness(benchmark::State& state) {
  const auto& xy = triangles();
  double d[9], k36[36];
  for (auto _ : state) {
    for (int e = 0; e < kElements; ++e) {
      k::elasticity_matrix(2e10 * (1.0 - 1e-6 * (e & 1023)), 0.25, k::PlaneKind::strain, d);
      k::cst_stiffness(&xy[6 * e], d, 1.0, k36);
      benchmark::DoNotOptimize(k36);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kElements);
}
BENCHMARK(BM_ElasticityAndStiffness)->Unit(benchmark::kMillisecond);

// What assembly computes: the isotropic moduli per element (damaged modulus), then the
// upper triangle of k without D's zeros.
void BM_IsotropicStiffnessUpper(benchmark::State& state) {
  const auto& xy = triangles();
  double ku[k::kUpperEntries];
  for (auto _ : state) {
    for (int e = 0; e < kElements; ++e) {
      const k::IsotropicModuli d =
          k::isotropic_moduli(2e10 * (1.0 - 1e-6 * (e & 1023)), 0.25, k::PlaneKind::strain);
      k::cst_isotropic_stiffness_upper(&xy[6 * e], d, 1.0, ku);
      benchmark::DoNotOptimize(ku);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kElements);
}
BENCHMARK(BM_IsotropicStiffnessUpper)->Unit(benchmark::kMillisecond);

// The internal-force pass: strain, stress and nodal force per element, forces stored.
void BM_StrainStressInternalForce(benchmark::State& state) {
  const auto& xy = triangles();
  const auto& u = displacements();
  std::vector<double> f(6 * kElements);
  double d[9];
  k::elasticity_matrix(2e10, 0.25, k::PlaneKind::strain, d);
  for (auto _ : state) {
    for (int e = 0; e < kElements; ++e) {
      double eps[3], sig[3];
      k::cst_strain(&xy[6 * e], &u[6 * e], eps);
      k::cst_stress(d, eps, sig);
      k::cst_internal_force(&xy[6 * e], sig, 1.0, &f[6 * e]);
    }
    benchmark::DoNotOptimize(f.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kElements);
}
BENCHMARK(BM_StrainStressInternalForce)->Unit(benchmark::kMillisecond);

// Damage evaluation per element on random strain states, stress from the undamaged D: the
// engine's post-solve damage pass. The states (mostly compressive, lateral ratio in
// [-0.5, 0.5]) give about 74 % intact, 16 % tension and 9 % shear outcomes.
void BM_EvaluateDamage(benchmark::State& state) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> normal(-3e-3, 3e-4), ratio(-0.5, 0.5), shear(-3e-4, 3e-4);
  std::vector<double> eps(3 * kElements), sig(3 * kElements);
  double d[9];
  k::elasticity_matrix(2e10, 0.25, k::PlaneKind::strain, d);
  for (int e = 0; e < kElements; ++e) {
    eps[3 * e] = normal(rng);
    eps[3 * e + 1] = eps[3 * e] * ratio(rng);
    eps[3 * e + 2] = shear(rng);
    k::cst_stress(d, &eps[3 * e], &sig[3 * e]);
  }
  k::DamageParams p;
  p.young = 2e10;
  p.poisson = 0.25;
  p.ft0 = 2e6;
  p.fc0 = k::compressive_strength(8e6, 0.5);
  p.mohr_coulomb = k::mohr_coulomb_factor(0.5);
  std::vector<double> w(kElements, 0.0);
  for (auto _ : state) {
    for (int e = 0; e < kElements; ++e) {
      w[e] = k::evaluate_damage(&eps[3 * e], &sig[3 * e], p, k::PlaneKind::strain, 0.0).w;
    }
    benchmark::DoNotOptimize(w.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kElements);
}
BENCHMARK(BM_EvaluateDamage)->Unit(benchmark::kMillisecond);

// Heterogeneity set-up: one Weibull draw per element (counter hash, log1p, pow, tgamma).
void BM_WeibullDraw(benchmark::State& state) {
  std::vector<double> out(kElements);
  for (auto _ : state) {
    for (int e = 0; e < kElements; ++e) out[e] = k::weibull_draw(2e10, 3.0, 42, e, 0);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kElements);
}
BENCHMARK(BM_WeibullDraw)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
