// Contact detection between blocks: block boundaries and vertex-edge candidates.
#include <gtest/gtest.h>
#include <oneapi/tbb/global_control.h>

#include <random>

#include "engine/contact/contact_detection.hpp"
#include "engine/mesh/mesh.hpp"
#include "engine/model/model.hpp"

namespace rockdd {
namespace {

/// Unit squares (two triangles each) at the given lower-left corners, each its own block and
/// body "b<i>".
Model squares(const std::vector<std::array<double, 2>>& corners, double size = 1.0) {
  Mesh mesh;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const auto n0 = static_cast<std::int32_t>(mesh.xy.size() / 2);
    const auto [x, y] = corners[i];
    for (const auto& [dx, dy] :
         std::vector<std::array<double, 2>>{{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
      mesh.xy.push_back(x + size * dx);
      mesh.xy.push_back(y + size * dy);
    }
    for (const int k : {0, 1, 2, 0, 2, 3}) mesh.triangles.push_back(n0 + k);
    mesh.element_surface.push_back(static_cast<std::int32_t>(i));
    mesh.element_surface.push_back(static_cast<std::int32_t>(i));
    mesh.surface_body.push_back("b" + std::to_string(i));
  }
  Scene scene;
  scene.file = "squares.toml";
  MaterialSpec m;
  m.body = "*";
  m.density = 1000;
  m.young = 1e9;
  m.poisson = 0.2;
  scene.materials.push_back(m);
  return build_model(scene, mesh);
}

ContactRules all_pairs(const Model& model) {
  ContactRules rules;
  rules.num_bodies = static_cast<std::int32_t>(model.sets.bodies.size());
  rules.allowed.assign(static_cast<std::size_t>(rules.num_bodies * rules.num_bodies), 1);
  rules.block_body.resize(static_cast<std::size_t>(model.num_blocks));
  for (std::int32_t e = 0; e < model.num_elements(); ++e)
    rules.block_body[model.element_block[e]] = model.element_body[e];
  return rules;
}

std::vector<double> positions(const Model& model) {
  std::vector<double> x(model.X.size());
  for (std::size_t d = 0; d < x.size(); ++d) x[d] = model.X[d] + model.u[d];
  return x;
}

TEST(BlockBoundary, SquareBoundaryIsCounterClockwise) {
  const Model model = squares({{0, 0}});
  const BlockBoundary b = extract_block_boundary(model);
  ASSERT_EQ(b.edge_block.size(), 4u);  // the diagonal is shared inside the block
  EXPECT_EQ(b.vertices.size(), 4u);
  double twice_area = 0;  // sum of a x b over the edges = 2 * area for a CCW boundary
  for (std::size_t i = 0; i < 4; ++i) {
    const auto a = b.edge_nodes[2 * i], c = b.edge_nodes[2 * i + 1];
    twice_area += model.X[2 * a] * model.X[2 * c + 1] - model.X[2 * c] * model.X[2 * a + 1];
  }
  EXPECT_NEAR(twice_area, 2.0, 1e-14);
}

TEST(DetectContacts, FacingSidesPairWithinReachOnly) {
  // Two squares 0.01 apart: within reach 0.02 the two facing vertices of each block pair with
  // the facing edge of the other (4 contacts); within 0.005 nothing.
  const Model model = squares({{0, 0}, {1.01, 0}});
  const BlockBoundary b = extract_block_boundary(model);
  const ContactRules rules = all_pairs(model);
  const auto near = detect_contacts(b, positions(model), rules, 0.02);
  ASSERT_EQ(near.size(), 4u);
  for (const auto& c : near) {
    const auto a = b.edge_nodes[2 * c.edge], e = b.edge_nodes[2 * c.edge + 1];
    EXPECT_NEAR(model.X[2 * a], model.X[2 * e], 1e-15) << "a vertical (facing) edge";
    EXPECT_NE(b.edge_block[c.edge], model.node_block[c.vertex]);
  }
  EXPECT_TRUE(detect_contacts(b, positions(model), rules, 0.005).empty());
  ContactRules none = rules;
  std::fill(none.allowed.begin(), none.allowed.end(), 0);
  EXPECT_TRUE(detect_contacts(b, positions(model), none, 0.02).empty());
}

TEST(DetectContacts, SameForOneAndTwoThreadsAndMatchesBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0, 30);
  std::vector<std::array<double, 2>> corners;
  for (int i = 0; i < 300; ++i) corners.push_back({U(rng), U(rng)});
  const Model model = squares(corners, 0.8);
  const BlockBoundary b = extract_block_boundary(model);
  const ContactRules rules = all_pairs(model);
  const auto x = positions(model);
  std::vector<ContactCandidate> one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = detect_contacts(b, x, rules, 0.1);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = detect_contacts(b, x, rules, 0.1);
  }
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].vertex, two[i].vertex);
    EXPECT_EQ(one[i].edge, two[i].edge);
  }
  // Brute force: every (vertex, other block) with some edge of that block within reach that
  // the vertex faces (outward normals opposed) must have exactly one candidate.
  std::vector<double> vn(2 * b.vertices.size(), 0.0);
  for (std::size_t e = 0; e < b.edge_block.size(); ++e) {
    const double* a = &x[2 * b.edge_nodes[2 * e]];
    const double* c = &x[2 * b.edge_nodes[2 * e + 1]];
    const double l = std::hypot(c[0] - a[0], c[1] - a[1]);
    for (const auto n : {b.edge_nodes[2 * e], b.edge_nodes[2 * e + 1]}) {
      const auto v = std::lower_bound(b.vertices.begin(), b.vertices.end(), n) - b.vertices.begin();
      vn[2 * v] += (c[1] - a[1]) / l;
      vn[2 * v + 1] -= (c[0] - a[0]) / l;
    }
  }
  std::size_t expected = 0;
  for (std::size_t v = 0; v < b.vertices.size(); ++v) {
    std::vector<std::int32_t> blocks;
    for (std::size_t e = 0; e < b.edge_block.size(); ++e) {
      if (b.edge_block[e] == b.vertex_block[v]) continue;
      const double* p = &x[2 * b.vertices[v]];
      const double* a = &x[2 * b.edge_nodes[2 * e]];
      const double* c = &x[2 * b.edge_nodes[2 * e + 1]];
      const double ex = c[0] - a[0], ey = c[1] - a[1];
      const double t =
          std::clamp(((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
      const double facing = ey * vn[2 * v] - ex * vn[2 * v + 1];  // (ey, -ex) . vertex normal
      if (std::hypot(p[0] - a[0] - t * ex, p[1] - a[1] - t * ey) <= 0.1 && facing < 0.0)
        blocks.push_back(b.edge_block[e]);
    }
    std::sort(blocks.begin(), blocks.end());
    expected +=
        static_cast<std::size_t>(std::unique(blocks.begin(), blocks.end()) - blocks.begin());
  }
  EXPECT_EQ(one.size(), expected);
  EXPECT_GT(expected, 10u);
}

}  // namespace
}  // namespace rockdd
