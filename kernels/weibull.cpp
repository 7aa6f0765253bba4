#include "kernels/weibull.hpp"

#include <cmath>

namespace rockdd::kernels {

namespace {
constexpr std::uint64_t kGolden = 0x9E3779B97F4A7C15ull;         // 2^64 / golden ratio, odd
constexpr std::uint64_t kElementSalt = 0x243F6A8885A308D3ull;    // pi, hex digits (odd)
constexpr std::uint64_t kParameterSalt = 0x13198A2E03707345ull;  // pi, next digits (odd)
}  // namespace

std::uint64_t splitmix64_mix(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

std::uint64_t counter_hash(std::uint64_t seed, std::uint64_t element, std::uint64_t parameter) {
  // One full mix per word: nearby counters (element e and e+1, parameter 0 and 1) differ in a
  // few low bits, and each mix spreads that difference over all 64 bits before the next word.
  std::uint64_t h = splitmix64_mix(seed + kGolden);
  h = splitmix64_mix(h ^ (element * kGolden + kElementSalt));
  return splitmix64_mix(h ^ (parameter * kGolden + kParameterSalt));
}

double uniform01_from_bits(std::uint64_t bits) {
  // 52 bits + 0.5 fit a double's 53-bit significand exactly, so no rounding can reach 1.
  return (static_cast<double>(bits >> 12) + 0.5) * 0x1.0p-52;
}

double uniform01(std::uint64_t seed, std::uint64_t element, std::uint64_t parameter) {
  return uniform01_from_bits(counter_hash(seed, element, parameter));
}

double weibull_scale(double mean, double m) {
  return mean / std::tgamma(1.0 + 1.0 / m);
}

double weibull_quantile(double u, double scale, double m) {
  // log1p keeps the small-u tail (the weak elements) accurate.
  return scale * std::pow(-std::log1p(-u), 1.0 / m);
}

double weibull_draw(double mean, double m, std::uint64_t seed, std::uint64_t element,
                    std::uint64_t parameter) {
  return weibull_quantile(uniform01(seed, element, parameter), weibull_scale(mean, m), m);
}

}  // namespace rockdd::kernels
