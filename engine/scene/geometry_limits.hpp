#pragma once
// The lengths and coordinates the engine can compute with: finite, neither so large that
// products of lengths overflow nor so small that they underflow, and not so far from the
// origin against the element size that rounding of the positions swamps the strains.
// The scene reader applies them to [mesh] keys, build_mesh to the nodes of .geo/.msh files.
#include <string>

namespace rockdd {

/// Largest length or |coordinate|, m. The longest products of lengths are of degree four (a
/// block's polar moment of inertia sum m r^2 with m = rho t A / 3 in the rotation correction;
/// Gmsh's 1D mesher: measured, a rectangle of side 1e80 comes out of Gmsh with zero-area
/// triangles, one of 1e70 meshes, one of 1e160 to 1e308 never returns). 1e50^4 = 1e200 leaves
/// 1e108 below the largest double (1.8e308) for densities, moduli and node counts.
constexpr double kLongestLength = 1e50;

/// Smallest length, m: the same degree-four products stay above 1e-200, far from the smallest
/// normal double (2.2e-308); below it element areas underflow to zero and B = 1 / (2A) is inf.
constexpr double kShortestLength = 1e-50;

/// Largest |coordinate| / element size. Co-rotated elements measure strain from current
/// positions X + u, rounded to 2.2e-16 |X|, so the strain error is about 2.2e-16 |X| / h. Rock
/// strains at failure are about ft / E = 2e-4; keeping the error below 1 % of that (2e-6)
/// gives |X| / h <= 1e10.
constexpr double kMostElementSizesFromOrigin = 1e10;

/// Whether `length` is finite and in [kShortestLength, kLongestLength].
bool length_in_range(double length);

/// Whether `x` is finite and |x| <= kLongestLength.
bool coordinate_in_range(double x);

/// Whether nodes as far as `farthest` (the largest |coordinate|) from the origin keep the
/// precision elements of size `element_size` need: farthest <= kMostElementSizesFromOrigin h.
bool keeps_precision(double farthest, double element_size);

/// "in [1e-50, 1e+50] m", for messages.
std::string length_range_text();

/// "coordinates within 1e+10 element sizes of the origin (...)", the expectation's words.
std::string precision_expectation();

}  // namespace rockdd
