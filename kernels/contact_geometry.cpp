#include "kernels/contact_geometry.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace rockdd::kernels {

VertexEdge vertex_edge(const double p[2], const double a[2], const double b[2]) {
  VertexEdge c;
  const double ex = b[0] - a[0], ey = b[1] - a[1];
  c.length = std::hypot(ex, ey);
  assert(c.length > 0.0);
  c.tangent[0] = ex / c.length;
  c.tangent[1] = ey / c.length;
  c.normal[0] = c.tangent[1];  // to the right of a->b: outward for a counter-clockwise boundary
  c.normal[1] = -c.tangent[0];
  const double px = p[0] - a[0], py = p[1] - a[1];
  c.xi = std::clamp((px * c.tangent[0] + py * c.tangent[1]) / c.length, 0.0, 1.0);
  // Measured from the projection q; beyond an end q is that end (the vertex-vertex limit),
  // and the gap is still the component of p - q along the edge's normal.
  const double dx = px - c.xi * ex, dy = py - c.xi * ey;
  c.gap = dx * c.normal[0] + dy * c.normal[1];
  c.distance = std::hypot(dx, dy);
  return c;
}

namespace {

/// d (direction . (p - q)) over (p, a, b) at fixed xi: (d, -(1 - xi) d, -xi d).
void relative_motion_gradient(const double direction[2], double xi, double out[6]) {
  for (int k = 0; k < 2; ++k) {
    out[k] = direction[k];
    out[2 + k] = -(1.0 - xi) * direction[k];
    out[4 + k] = -xi * direction[k];
  }
}

}  // namespace

void gap_gradient(const VertexEdge& c, double g[6]) {
  relative_motion_gradient(c.normal, c.xi, g);
}

void slip_gradient(const VertexEdge& c, double s[6]) {
  relative_motion_gradient(c.tangent, c.xi, s);
}

}  // namespace rockdd::kernels
