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

void gap_gradient(const VertexEdge& c, double g[6]) {
  g[0] = c.normal[0];
  g[1] = c.normal[1];
  g[2] = -(1.0 - c.xi) * c.normal[0];
  g[3] = -(1.0 - c.xi) * c.normal[1];
  g[4] = -c.xi * c.normal[0];
  g[5] = -c.xi * c.normal[1];
}

void slip_gradient(const VertexEdge& c, double s[6]) {
  s[0] = c.tangent[0];
  s[1] = c.tangent[1];
  s[2] = -(1.0 - c.xi) * c.tangent[0];
  s[3] = -(1.0 - c.xi) * c.tangent[1];
  s[4] = -c.xi * c.tangent[0];
  s[5] = -c.xi * c.tangent[1];
}

}  // namespace rockdd::kernels
