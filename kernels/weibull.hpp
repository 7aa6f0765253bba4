#pragma once
// Reproducible per-element Weibull draws (paper eq. 1) from a counter-based generator.
//
// Generator: the value for (seed, element, parameter) is a hash of the three integers, not
// the next state of a stream, so a draw depends on nothing else: not on thread count, on the
// order elements are visited, or on how many other draws were made. The hash chains the
// SplitMix64 finalizer (Steele, Lea & Flood 2014; the mixing function of Java's
// SplittableRandom), a bijection on 64 bits with full avalanche:
//   h = mix(seed + G), h = mix(h ^ (element * G + C1)), h = mix(h ^ (parameter * G + C2)),
// with G = 0x9E3779B97F4A7C15 (odd, so each step is a bijection in its integer for fixed
// earlier ones) and C1, C2 fixed odd constants. The top 52 bits of h give a uniform number
// in (0, 1) on a grid that never touches 0 or 1.
//
// Distribution: F(x) = 1 - exp(-(x/u0)^m) (eq. 1 has the exponent misplaced: the PDF is
// m/u0 (x/u0)^(m-1) exp(-(x/u0)^m)), scale u0 = mean / Gamma(1 + 1/m) so the scene's mean
// is the distribution's mean.

#include <cstdint>

namespace rockdd::kernels {

/// SplitMix64 finalizer: a fixed bijective 64-bit mixing function.
std::uint64_t splitmix64_mix(std::uint64_t x);

/// Counter-based hash of (seed, element, parameter): deterministic, stateless.
std::uint64_t counter_hash(std::uint64_t seed, std::uint64_t element, std::uint64_t parameter);

/// Uniform number from the top 52 bits: (k + 0.5) / 2^52, in [2^-53, 1 - 2^-53], never 0 or 1.
double uniform01_from_bits(std::uint64_t bits);

/// Uniform (0, 1) draw for one parameter of one element.
double uniform01(std::uint64_t seed, std::uint64_t element, std::uint64_t parameter);

/// Weibull scale u0 = mean / Gamma(1 + 1/m) for shape m > 0.
double weibull_scale(double mean, double m);

/// Inverse Weibull CDF: u0 (-ln(1 - u))^(1/m) for u in (0, 1).
double weibull_quantile(double u, double scale, double m);

/// Weibull draw with the given mean and shape m for one parameter of one element.
double weibull_draw(double mean, double m, std::uint64_t seed, std::uint64_t element,
                    std::uint64_t parameter);

}  // namespace rockdd::kernels
