#pragma once
// Vertex-to-edge contact geometry in 2D (DDA's basic contact; vertex-vertex is its limit
// when the projection falls on an end of the edge). Pure functions over plain arrays.
//
// Conventions: an edge a->b belongs to a counter-clockwise boundary, so its body lies on
// the left and its outward normal points to the right: n = (t_y, -t_x), t = (b - a)/|b - a|.
// Gradients are 6-vectors over the displacements (p_x, p_y, a_x, a_y, b_x, b_y).

namespace rockdd::kernels {

/// Geometry of a vertex p against the edge a->b.
struct VertexEdge {
  double gap = 0;              // (p - q) . n, q the projection of p on the edge; < 0: penetration
  double xi = 0;               // q = a + xi (b - a), xi clamped to [0, 1]
  double normal[2] = {0, 0};   // unit outward normal of the edge
  double tangent[2] = {0, 0};  // unit tangent a->b
  double length = 0;           // |b - a|
  double distance = 0;         // |p - q| (vertex-vertex distance when xi is clamped)
};

/// Gap, projection, normal and tangent of vertex p against edge a->b (length > 0 required).
VertexEdge vertex_edge(const double p[2], const double a[2], const double b[2]);

/// Linearised gap: d gap = g . (du_p, du_a, du_b) at fixed xi and normal.
void gap_gradient(const VertexEdge& c, double g[6]);

/// Linearised tangential slip of p relative to the edge's material point at xi:
/// d slip = s . (du_p, du_a, du_b) at fixed xi and tangent.
void slip_gradient(const VertexEdge& c, double s[6]);

}  // namespace rockdd::kernels
