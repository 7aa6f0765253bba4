// Counter-based Weibull draws: distribution (mean, shape) and reproducibility.
#include "kernels/weibull.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace {

namespace k = rockdd::kernels;

constexpr int kN = 100000;
constexpr std::uint64_t kSeed = 20240611;

std::vector<double> draws(double mean, double m, std::uint64_t seed, std::uint64_t parameter) {
  std::vector<double> x(kN);
  for (int e = 0; e < kN; ++e) x[e] = k::weibull_draw(mean, m, seed, e, parameter);
  return x;
}

// Maximum-likelihood Weibull shape: the root of
// g(m) = sum x^m ln x / sum x^m - 1/m - mean(ln x), increasing in m; found by bisection on
// x / mean (scale-free, so x^m cannot overflow).
double fitted_shape(const std::vector<double>& x) {
  double mean = 0.0;
  for (double v : x) mean += v;
  mean /= x.size();
  std::vector<double> lx(x.size());
  double mean_log = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    lx[i] = std::log(x[i] / mean);
    mean_log += lx[i];
  }
  mean_log /= x.size();
  auto g = [&](double m) {
    double s0 = 0.0, s1 = 0.0;
    for (double l : lx) {
      const double p = std::exp(m * l);
      s0 += p;
      s1 += p * l;
    }
    return s1 / s0 - 1.0 / m - mean_log;
  };
  double lo = 0.05, hi = 100.0;
  for (int it = 0; it < 60; ++it) {
    const double mid = std::sqrt(lo * hi);
    (g(mid) < 0.0 ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= a.size();
  mb /= b.size();
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

// Kolmogorov-Smirnov distance of a sample from a CDF.
template <class Cdf>
double ks_distance(std::vector<double> x, Cdf cdf) {
  std::sort(x.begin(), x.end());
  double d = 0.0;
  const double n = x.size();
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double f = cdf(x[i]);
    d = std::max({d, (i + 1) / n - f, f - i / n});
  }
  return d;
}

TEST(Weibull, MeanAndShapeOfTheSampleMatchTheScene) {
  // u0 = mean / Gamma(1 + 1/m) makes the scene's value the mean (sample mean within 1 %), and
  // the maximum-likelihood shape of 10^5 draws is within 5 % of m. The KS distance to
  // F = 1 - exp(-(x/u0)^m) stays below 1.63/sqrt(n) (the 1 % critical value). Each m uses its
  // own parameter index: with one shared uniform sample the three fits would be one fit scaled.
  const double mean = 3.0e10;
  std::uint64_t parameter = 0;
  for (double m : {1.5, 3.0, 10.0}) {
    const std::vector<double> x = draws(mean, m, kSeed, parameter++);
    double s = 0.0;
    for (double v : x) s += v;
    const double mean_err = std::fabs(s / kN - mean) / mean;
    const double m_fit = fitted_shape(x);
    const double m_err = std::fabs(m_fit - m) / m;
    const double u0 = k::weibull_scale(mean, m);
    const double ks = ks_distance(x, [&](double v) { return -std::expm1(-std::pow(v / u0, m)); });
    std::printf(
        "[ weibull  ] m = %4.1f: mean error %.3f %%, fitted m %.4f (error %.3f %%), "
        "KS %.5f\n",
        m, 100 * mean_err, m_fit, 100 * m_err, ks);
    EXPECT_LT(mean_err, 0.01) << "m = " << m;
    EXPECT_LT(m_err, 0.05) << "m = " << m;
    EXPECT_LT(ks, 1.63 / std::sqrt(double(kN))) << "m = " << m;
    EXPECT_GT(*std::min_element(x.begin(), x.end()), 0.0);
  }
}

TEST(Weibull, ScaleFromTheMean) {
  // u0 = mean / Gamma(1 + 1/m): m = 1 is the exponential (u0 = mean); m = 2 has
  // Gamma(3/2) = sqrt(pi)/2.
  EXPECT_DOUBLE_EQ(k::weibull_scale(5.0, 1.0), 5.0);
  EXPECT_DOUBLE_EQ(k::weibull_scale(5.0, 2.0), 5.0 / (std::sqrt(M_PI) / 2));
  // Quantile at F = 1 - 1/e is the scale whatever m.
  for (double m : {1.5, 3.0, 10.0})
    EXPECT_DOUBLE_EQ(k::weibull_quantile(-std::expm1(-1.0), 7.0, m), 7.0);
}

TEST(Weibull, UniformIsStrictlyInsideTheUnitInterval) {
  // The extreme hash values map to 2^-53 and 1 - 2^-53, never to 0 or 1; draws are uniform
  // (mean 1/2 within 4 standard errors, KS below the 1 % critical value).
  EXPECT_EQ(k::uniform01_from_bits(0), 0x1.0p-53);
  EXPECT_EQ(k::uniform01_from_bits(~std::uint64_t{0}), 1.0 - 0x1.0p-53);
  EXPECT_LT(k::uniform01_from_bits(~std::uint64_t{0}), 1.0);
  EXPECT_TRUE(std::isfinite(k::weibull_quantile(1.0 - 0x1.0p-53, 1.0, 1.5)));
  EXPECT_GT(k::weibull_quantile(0x1.0p-53, 1.0, 10.0), 0.0);
  std::vector<double> u(kN);
  double s = 0.0;
  for (int e = 0; e < kN; ++e) {
    u[e] = k::uniform01(kSeed, e, 3);
    EXPECT_GT(u[e], 0.0);
    EXPECT_LT(u[e], 1.0);
    s += u[e];
  }
  EXPECT_NEAR(s / kN, 0.5, 4 * std::sqrt(1.0 / 12 / kN));
  EXPECT_LT(ks_distance(u, [](double v) { return v; }), 1.63 / std::sqrt(double(kN)));
}

TEST(Weibull, SplitMix64FinalizerMatchesTheReference) {
  // The first output of SplitMix64 seeded with 0 is mix(0x9E3779B97F4A7C15) =
  // 0xE220A8397B1DCDAF (reference sequence of Steele et al.'s generator).
  EXPECT_EQ(k::splitmix64_mix(0x9E3779B97F4A7C15ull), 0xE220A8397B1DCDAFull);
}

TEST(Weibull, DrawsAreDeterministic) {
  // Same (seed, element, parameter): bit-identical value, however often it is asked for.
  for (std::uint64_t e : {0ull, 1ull, 12345ull, 1ull << 40}) {
    const double a = k::weibull_draw(2e6, 3.0, kSeed, e, 1);
    EXPECT_EQ(a, k::weibull_draw(2e6, 3.0, kSeed, e, 1));
    EXPECT_EQ(k::uniform01(kSeed, e, 1), k::uniform01(kSeed, e, 1));
  }
}

TEST(Weibull, ReverseOrderGivesTheSameValues) {
  // Stateless: drawing elements in reverse (or any) order gives the same value per element.
  std::vector<double> fwd(kN), rev(kN);
  for (int e = 0; e < kN; ++e) fwd[e] = k::weibull_draw(1.0, 1.5, kSeed, e, 2);
  for (int e = kN - 1; e >= 0; --e) rev[e] = k::weibull_draw(1.0, 1.5, kSeed, e, 2);
  EXPECT_EQ(fwd, rev);
}

TEST(Weibull, ParametersElementsAndSeedsAreIndependent) {
  // Different parameter index (same element), neighbouring element and neighbouring seed give
  // uncorrelated uniforms: |r| < 0.015 (about 5 standard errors of 1/sqrt(n)), and differ.
  std::vector<double> p0(kN), p1(kN), next(kN), seed1(kN);
  for (int e = 0; e < kN; ++e) {
    p0[e] = k::uniform01(kSeed, e, 0);
    p1[e] = k::uniform01(kSeed, e, 1);
    next[e] = k::uniform01(kSeed, e + 1, 0);
    seed1[e] = k::uniform01(kSeed + 1, e, 0);
  }
  const double r_param = correlation(p0, p1);
  const double r_elem = correlation(p0, next);
  const double r_seed = correlation(p0, seed1);
  std::printf("[ weibull  ] correlation: parameter %.5f, element %.5f, seed %.5f\n", r_param,
              r_elem, r_seed);
  EXPECT_LT(std::fabs(r_param), 0.015);
  EXPECT_LT(std::fabs(r_elem), 0.015);
  EXPECT_LT(std::fabs(r_seed), 0.015);
  int same = 0;
  for (int e = 0; e < kN; ++e) same += (p0[e] == p1[e]) + (p0[e] == seed1[e]);
  EXPECT_EQ(same, 0);
  // Parameter index swapped with element index is a different stream too.
  EXPECT_NE(k::uniform01(kSeed, 1, 2), k::uniform01(kSeed, 2, 1));
}

}  // namespace
