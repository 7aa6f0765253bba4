// Contact detection between blocks: block boundaries and vertex-edge candidates.
#include <gtest/gtest.h>
#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include "engine/contact/broad_phase.hpp"
#include "engine/contact/contact_detection.hpp"
#include "engine/mesh/mesh.hpp"
#include "engine/model/model.hpp"
#include "kernels/contact_geometry.hpp"

namespace rockdd {
namespace {

/// Squares (two triangles each) at the given lower-left corners with the given sides, each its
/// own block and body "b<i>".
Model squares(const std::vector<std::array<double, 2>>& corners, const std::vector<double>& sides) {
  Mesh mesh;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const auto n0 = static_cast<std::int32_t>(mesh.xy.size() / 2);
    const auto [x, y] = corners[i];
    for (const auto& [dx, dy] :
         std::vector<std::array<double, 2>>{{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
      mesh.xy.push_back(x + sides[i] * dx);
      mesh.xy.push_back(y + sides[i] * dy);
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

/// Squares of one side at the given lower-left corners.
Model squares(const std::vector<std::array<double, 2>>& corners, double size = 1.0) {
  return squares(corners, std::vector<double>(corners.size(), size));
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

TEST(DetectContacts, AnInertBlockTouchesNothing) {
  // A block of fully broken elements is the open crack (ContactRules::inert): neither its
  // vertices nor its edges take part, whatever lies within reach. Three squares in a row,
  // 0.01 apart: 4 contacts at each of the two gaps; with the middle one inert, none; with
  // the last one inert, the 4 of the first gap.
  const Model model = squares({{0, 0}, {1.01, 0}, {2.02, 0}});
  const BlockBoundary b = extract_block_boundary(model);
  ContactRules rules = all_pairs(model);
  ASSERT_EQ(detect_contacts(b, positions(model), rules, 0.02).size(), 8u);
  auto block_at = [&](double x) {
    for (std::int32_t n = 0; n < model.num_nodes(); ++n)
      if (std::abs(model.X[2 * n] - x) < 1e-12) return model.node_block[n];
    return -1;
  };
  rules.inert.assign(static_cast<std::size_t>(model.num_blocks), 0);
  rules.inert[block_at(1.01)] = 1;
  EXPECT_TRUE(detect_contacts(b, positions(model), rules, 0.02).empty());
  std::fill(rules.inert.begin(), rules.inert.end(), 0);
  rules.inert[block_at(3.02)] = 1;
  const auto left = detect_contacts(b, positions(model), rules, 0.02);
  EXPECT_EQ(left.size(), 4u);
  for (const auto& c : left) {
    EXPECT_FALSE(rules.inert[b.edge_block[c.edge]]);
    EXPECT_FALSE(rules.inert[model.node_block[c.vertex]]);
  }
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

/// A random pile for the broad phase: 1000 squares of side 0.5-1.5 and one of side 20 over a
/// 70 x 70 field, each block turned about its centre by a random angle and each corner moved
/// by up to 0.05: blocks overlap, touch or stand apart, with edges of very different lengths.
struct Pile {
  Model model;
  BlockBoundary boundary;
  ContactRules rules;
  std::vector<double> x;  // current positions
};

Pile random_pile(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> field(0, 70), side(0.5, 1.5), turn(0, 6.3),
      nudge(-0.05, 0.05);
  std::vector<std::array<double, 2>> corners{{25, 25}};
  std::vector<double> sides{20};
  for (int i = 0; i < 1000; ++i) {
    corners.push_back({field(rng), field(rng)});
    sides.push_back(side(rng));
  }
  Pile pile{squares(corners, sides), {}, {}, {}};
  const Model& m = pile.model;
  pile.boundary = extract_block_boundary(m);
  pile.rules = all_pairs(m);
  std::vector<double> centre(2 * static_cast<std::size_t>(m.num_blocks), 0.0), angle;
  for (std::int32_t n = 0; n < m.num_nodes(); ++n)
    for (int d = 0; d < 2; ++d) centre[2 * m.node_block[n] + d] += 0.25 * m.X[2 * n + d];
  for (std::int32_t k = 0; k < m.num_blocks; ++k) angle.push_back(turn(rng));
  pile.x.resize(m.X.size());
  for (std::int32_t n = 0; n < m.num_nodes(); ++n) {
    const double* c = &centre[2 * m.node_block[n]];
    const double t = angle[m.node_block[n]], dx = m.X[2 * n] - c[0], dy = m.X[2 * n + 1] - c[1];
    pile.x[2 * n] = c[0] + std::cos(t) * dx - std::sin(t) * dy + nudge(rng);
    pile.x[2 * n + 1] = c[1] + std::sin(t) * dx + std::cos(t) * dy + nudge(rng);
  }
  return pile;
}

/// Distance from p to the segment a-b.
double segment_distance(const double* p, const double* a, const double* b) {
  const double ex = b[0] - a[0], ey = b[1] - a[1];
  const double t =
      std::clamp(((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
  return std::hypot(p[0] - a[0] - t * ex, p[1] - a[1] - t * ey);
}

TEST(BroadPhase, NeverMissesAPairTheNarrowCheckFinds) {
  const Pile pile = random_pile(5);
  const BlockBoundary& b = pile.boundary;
  const double reach = 0.3;
  for (const double inflation : {0.0, 0.05}) {
    const double margin = 0.5 * reach + inflation;
    const auto flag = flag_edges_near_other_blocks(b, pile.x, pile.rules, margin);
    const auto pairs = candidate_block_pairs(b, pile.x, pile.rules, margin);
    const std::set<std::array<std::int32_t, 2>> pair_set(pairs.begin(), pairs.end());
    std::size_t found = 0;
    for (std::size_t e = 0; e < b.edge_block.size(); ++e)
      for (std::size_t f = 0; f < b.edge_block.size(); ++f) {
        if (b.edge_block[e] == b.edge_block[f]) continue;
        // Vertex a of edge f within 2 * margin of edge e: e, f and their blocks are candidates.
        const std::int32_t n = b.edge_nodes[2 * f];
        if (segment_distance(&pile.x[2 * n], &pile.x[2 * b.edge_nodes[2 * e]],
                             &pile.x[2 * b.edge_nodes[2 * e + 1]]) > 2 * margin)
          continue;
        ++found;
        EXPECT_TRUE(flag[e]) << "edge " << e;
        EXPECT_TRUE(flag[f]) << "edge " << f;
        const std::int32_t p = b.edge_block[e], q = b.edge_block[f];
        EXPECT_TRUE(pair_set.count({std::min(p, q), std::max(p, q)})) << p << " " << q;
      }
    EXPECT_GT(found, 1000u);
  }
}

TEST(BroadPhase, MatchesBruteForceBoxOverlapAndPairsOnlyDifferentBlocks) {
  const Pile pile = random_pile(6);
  const BlockBoundary& b = pile.boundary;
  const double margin = 0.2;
  const std::size_t num_edges = b.edge_block.size();
  std::vector<double> box(4 * num_edges);
  for (std::size_t e = 0; e < num_edges; ++e)
    for (int d = 0; d < 2; ++d) {
      const double u = pile.x[2 * b.edge_nodes[2 * e] + d],
                   w = pile.x[2 * b.edge_nodes[2 * e + 1] + d];
      box[4 * e + d] = std::min(u, w) - margin;
      box[4 * e + 2 + d] = std::max(u, w) + margin;
    }
  std::vector<std::uint8_t> expected_flag(num_edges, 0);
  std::set<std::array<std::int32_t, 2>> expected_pairs;
  for (std::size_t e = 0; e < num_edges; ++e)
    for (std::size_t f = e + 1; f < num_edges; ++f) {
      const double* p = &box[4 * e];
      const double* q = &box[4 * f];
      if (b.edge_block[e] == b.edge_block[f] || p[0] > q[2] || q[0] > p[2] || p[1] > q[3] ||
          q[1] > p[3])
        continue;
      expected_flag[e] = expected_flag[f] = 1;
      expected_pairs.insert(
          {std::min(b.edge_block[e], b.edge_block[f]), std::max(b.edge_block[e], b.edge_block[f])});
    }
  EXPECT_EQ(flag_edges_near_other_blocks(b, pile.x, pile.rules, margin), expected_flag);
  const auto pairs = candidate_block_pairs(b, pile.x, pile.rules, margin);
  EXPECT_EQ(std::vector(expected_pairs.begin(), expected_pairs.end()), pairs);
  for (const auto& [p, q] : pairs) EXPECT_LT(p, q);
  EXPECT_GT(pairs.size(), 100u);
  // The big block's long edges cross many cells; some small blocks stand alone.
  EXPECT_TRUE(std::count(expected_flag.begin(), expected_flag.end(), 0) > 0);
}

TEST(BroadPhase, NothingWhereNoBlocksMayTouch) {
  // One block alone, and two touching blocks whose bodies the rules keep apart.
  const Model one = squares({{0, 0}});
  const BlockBoundary b1 = extract_block_boundary(one);
  const auto x1 = positions(one);
  const auto flag1 = flag_edges_near_other_blocks(b1, x1, all_pairs(one), 1.0);
  EXPECT_EQ(std::count(flag1.begin(), flag1.end(), 1), 0);
  EXPECT_TRUE(candidate_block_pairs(b1, x1, all_pairs(one), 1.0).empty());
  const Model two = squares({{0, 0}, {1, 0}});
  const BlockBoundary b2 = extract_block_boundary(two);
  const auto x2 = positions(two);
  ContactRules apart = all_pairs(two);
  apart.allowed = {1, 0, 0, 1};  // each body with itself only
  const auto flag2 = flag_edges_near_other_blocks(b2, x2, apart, 0.1);
  EXPECT_EQ(std::count(flag2.begin(), flag2.end(), 1), 0);
  EXPECT_EQ(candidate_block_pairs(b2, x2, all_pairs(two), 0.1),
            (std::vector<std::array<std::int32_t, 2>>{{0, 1}}));
}

TEST(BroadPhase, SameForOneAndTwoThreads) {
  const Pile pile = random_pile(7);
  std::vector<std::uint8_t> flag[2];
  std::vector<std::array<std::int32_t, 2>> pairs[2];
  for (const int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    flag[threads - 1] = flag_edges_near_other_blocks(pile.boundary, pile.x, pile.rules, 0.2);
    pairs[threads - 1] = candidate_block_pairs(pile.boundary, pile.x, pile.rules, 0.2);
  }
  EXPECT_EQ(flag[0], flag[1]);
  EXPECT_EQ(pairs[0], pairs[1]);
}

/// detect_contacts as a serial pass over every edge and vertex, without broad phase or tree.
std::vector<ContactCandidate> reference_contacts(const BlockBoundary& b,
                                                 const std::vector<double>& x,
                                                 const ContactRules& rules, double reach) {
  std::vector<double> vn(2 * b.vertices.size(), 0.0);
  auto vertex = [&](std::int32_t n) {
    return std::lower_bound(b.vertices.begin(), b.vertices.end(), n) - b.vertices.begin();
  };
  for (std::size_t e = 0; e < b.edge_block.size(); ++e) {
    const double* a = &x[2 * b.edge_nodes[2 * e]];
    const double* c = &x[2 * b.edge_nodes[2 * e + 1]];
    const double l = std::hypot(c[0] - a[0], c[1] - a[1]);
    for (const auto n : {b.edge_nodes[2 * e], b.edge_nodes[2 * e + 1]}) {
      vn[2 * vertex(n)] += (c[1] - a[1]) / l;
      vn[2 * vertex(n) + 1] -= (c[0] - a[0]) / l;
    }
  }
  // Best edge per (vertex, other block): projects inside, then largest gap, then lowest edge.
  std::map<std::pair<std::int32_t, std::int32_t>, std::tuple<bool, double, std::int32_t>> best;
  for (std::size_t e = 0; e < b.edge_block.size(); ++e)
    for (std::size_t v = 0; v < b.vertices.size(); ++v) {
      const std::int32_t vb = b.vertex_block[v], eb = b.edge_block[e];
      if (vb == eb ||
          !rules.allowed[rules.block_body[vb] * rules.num_bodies + rules.block_body[eb]])
        continue;
      const auto c = kernels::vertex_edge(&x[2 * b.vertices[v]], &x[2 * b.edge_nodes[2 * e]],
                                          &x[2 * b.edge_nodes[2 * e + 1]]);
      if (c.distance > reach || !(c.normal[0] * vn[2 * v] + c.normal[1] * vn[2 * v + 1] < -0.05))
        continue;
      const std::tuple<bool, double, std::int32_t> key{c.xi > 0.0 && c.xi < 1.0, c.gap,
                                                       static_cast<std::int32_t>(e)};
      const auto [it, inserted] = best.try_emplace({b.vertices[v], eb}, key);
      if (inserted) continue;
      const auto& [interior, gap, edge] = it->second;
      if (std::tuple(std::get<0>(key), std::get<1>(key), -std::get<2>(key)) >
          std::tuple(interior, gap, -edge))
        it->second = key;
    }
  std::vector<ContactCandidate> out;
  for (const auto& [vertex_block, value] : best)
    out.push_back({vertex_block.first, std::get<2>(value)});
  std::sort(out.begin(), out.end(), [](const ContactCandidate& p, const ContactCandidate& q) {
    return p.vertex != q.vertex ? p.vertex < q.vertex : p.edge < q.edge;
  });
  return out;
}

TEST(DetectContacts, MatchesSerialReferenceOnADistortedPileWhateverTheInflation) {
  const Pile pile = random_pile(8);
  const auto expected = reference_contacts(pile.boundary, pile.x, pile.rules, 0.3);
  ASSERT_GT(expected.size(), 500u);
  for (const double inflation : {0.0, 0.1, 2.0}) {
    const auto found = detect_contacts(pile.boundary, pile.x, pile.rules, 0.3, inflation);
    ASSERT_EQ(found.size(), expected.size()) << "inflation " << inflation;
    for (std::size_t i = 0; i < found.size(); ++i) {
      EXPECT_EQ(found[i].vertex, expected[i].vertex);
      EXPECT_EQ(found[i].edge, expected[i].edge);
    }
  }
}

}  // namespace
}  // namespace rockdd
