// Vertex-edge contact geometry (kernels/contact_geometry): gap, projection and gradients.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/contact_geometry.hpp"

namespace rockdd::kernels {
namespace {

TEST(VertexEdge, GapIsPositiveOutsideAndNegativeInside) {
  // Edge a->b along +x: a counter-clockwise body lies above it (on its left), so the outward
  // normal is -y; a vertex below the edge is outside (gap > 0), above it penetrates.
  const double a[2] = {0, 0}, b[2] = {2, 0};
  const double below[2] = {0.5, -0.1}, above[2] = {1.5, 0.2};
  const VertexEdge out = vertex_edge(below, a, b), in = vertex_edge(above, a, b);
  EXPECT_NEAR(out.gap, 0.1, 1e-15);
  EXPECT_NEAR(in.gap, -0.2, 1e-15);
  EXPECT_NEAR(out.xi, 0.25, 1e-15);
  EXPECT_NEAR(in.xi, 0.75, 1e-15);
  EXPECT_NEAR(out.normal[1], -1.0, 1e-15);
  EXPECT_NEAR(out.length, 2.0, 1e-15);
}

TEST(VertexEdge, BeyondAnEndTheProjectionClampsToTheEndPoint) {
  // Vertex-vertex limit: xi = 1 and the distance is |p - b|.
  const double a[2] = {0, 0}, b[2] = {1, 0}, p[2] = {1.3, -0.4};
  const VertexEdge c = vertex_edge(p, a, b);
  EXPECT_EQ(c.xi, 1.0);
  EXPECT_NEAR(c.distance, 0.5, 1e-15);
  EXPECT_NEAR(c.gap, 0.4, 1e-15);
}

TEST(VertexEdge, NormalsOfACounterClockwiseTrianglePointOutwards) {
  const double x[3][2] = {{0, 0}, {3, 0.5}, {1, 2}};
  const double cx = (x[0][0] + x[1][0] + x[2][0]) / 3, cy = (x[0][1] + x[1][1] + x[2][1]) / 3;
  for (int k = 0; k < 3; ++k) {
    const double* a = x[k];
    const double* b = x[(k + 1) % 3];
    const double centroid[2] = {cx, cy};
    const VertexEdge c = vertex_edge(centroid, a, b);
    EXPECT_LT(c.gap, 0.0) << "the centroid is inside, behind every face";
    EXPECT_NEAR(std::hypot(c.normal[0], c.normal[1]), 1.0, 1e-15);
    EXPECT_NEAR(c.normal[0] * c.tangent[0] + c.normal[1] * c.tangent[1], 0.0, 1e-15);
  }
}

TEST(VertexEdge, GradientsMatchCentralDifferences) {
  // d gap / d(u_p, u_a, u_b) = (n, -(1 - xi) n, -xi n) at fixed xi and normal; checked
  // against central differences of the gap (1e-6 relative) for random geometry.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    double x[6] = {U(rng),      U(rng), -1.0 + 0.2 * U(rng), 0.2 * U(rng), 1.0 + 0.2 * U(rng),
                   0.2 * U(rng)};
    x[0] = 0.5 * x[0];  // keep the projection inside the edge
    const VertexEdge c = vertex_edge(x, x + 2, x + 4);
    double g[6], s[6];
    gap_gradient(c, g);
    slip_gradient(c, s);
    for (int i = 0; i < 6; ++i) {
      const double h = 1e-6;
      double xp[6], xm[6];
      std::copy(x, x + 6, xp);
      std::copy(x, x + 6, xm);
      xp[i] += h;
      xm[i] -= h;
      // The gap is stationary in xi (q is the closest point), so its derivative is exact.
      const double dgap =
          (vertex_edge(xp, xp + 2, xp + 4).gap - vertex_edge(xm, xm + 2, xm + 4).gap) / (2 * h);
      EXPECT_NEAR(g[i], dgap, 1e-6) << "trial " << trial << " dof " << i;
    }
    // Rigid translation of all three points changes neither gap nor slip.
    double sum_g = 0, sum_s = 0;
    for (int k = 0; k < 3; ++k) {
      sum_g += g[2 * k] * 0.3 + g[2 * k + 1] * -0.7;
      sum_s += s[2 * k] * 0.3 + s[2 * k + 1] * -0.7;
    }
    EXPECT_NEAR(sum_g, 0.0, 1e-14);
    EXPECT_NEAR(sum_s, 0.0, 1e-14);
  }
}

}  // namespace
}  // namespace rockdd::kernels
