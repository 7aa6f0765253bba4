// Assembly: the stiffness pattern and values, internal force, and thread independence.
#include <gtest/gtest.h>
#include <oneapi/tbb/global_control.h>

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cstring>

#include "engine/assembly/assemble_stiffness.hpp"
#include "engine/assembly/element_coloring.hpp"
#include "engine/assembly/for_each_element_by_color.hpp"
#include "engine/assembly/internal_force.hpp"
#include "engine/assembly/modulus_change.hpp"
#include "engine/assembly/stiffness_layout.hpp"
#include "engine/mesh/mesh.hpp"
#include "engine/model/model.hpp"
#include "support/scene_run.hpp"
#include "support/scene_toml.hpp"
#include "support/temp_dir.hpp"

namespace rockdd {
namespace {

const std::string kRectangle = test::scene_table("assembly", "static", "plane = \"stress\"\n") +
                               test::rectangle_mesh(2.0, 1.0, 0.2) +
                               test::material("*", 2500.0, 30e9, 0.25) + test::fixed("left");

struct Assembled {
  Model model;
  StiffnessLayout layout;
  ElementColoring coloring;
  std::vector<std::int32_t> equation;
  std::vector<double> values;
};

/// Assembles the scene's stiffness with every dof free or with the left edge eliminated.
Assembled assemble(const std::string& text, bool all_free, double mass_coefficient = 0.0) {
  test::TempDir dir;
  const Scene scene = test::scene_from_text(text, dir.path());
  Assembled a{build_scene_model(scene), {}, {}, {}, {}};
  a.equation.assign(a.model.X.size(), 0);
  std::int32_t next = 0;
  std::vector<std::uint8_t> fixed(a.model.X.size(), 0);
  if (!all_free)
    for (std::size_t i = 0; i + 1 < a.model.sets.curve_edges["left"].size(); ++i)
      for (int c = 0; c < 2; ++c) fixed[2 * a.model.sets.curve_edges["left"][i] + c] = 1;
  for (std::size_t d = 0; d < a.equation.size(); ++d) a.equation[d] = fixed[d] ? -1 : next++;
  a.coloring = color_elements(a.model.conn, a.model.num_nodes());
  a.layout = build_stiffness_layout(a.model.conn, a.model.num_nodes(), a.equation);
  a.values.assign(static_cast<std::size_t>(a.layout.pattern.nnz()), 0.0);
  assemble_stiffness(a.model, a.coloring, a.layout, a.equation, mass_coefficient, a.values);
  return a;
}

Eigen::MatrixXd dense(const SparsityPattern& p, const std::vector<double>& values) {
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(p.n, p.n);
  for (std::int32_t j = 0; j < p.n; ++j)
    for (std::int32_t q = p.col_ptr[j]; q < p.col_ptr[j + 1]; ++q) {
      k(p.row_idx[q], j) = values[q];
      k(j, p.row_idx[q]) = values[q];
    }
  return k;
}

/// Checks that the chunks of each colour share no node and that every element is visited
/// exactly once, in chunks of consecutive elements.
void expect_valid_coloring(const ElementColoring& coloring, std::span<const std::int32_t> conn,
                           std::int32_t num_nodes) {
  const auto num_elements = static_cast<std::int32_t>(conn.size() / 3);
  ASSERT_EQ(coloring.num_elements, num_elements);
  std::vector<int> visits(static_cast<std::size_t>(num_elements), 0);
  for (std::int32_t c = 0; c < coloring.num_colors(); ++c) {
    std::vector<std::int32_t> owner(static_cast<std::size_t>(num_nodes), -1);
    for (std::int32_t i = coloring.offset[c]; i < coloring.offset[c + 1]; ++i) {
      const std::int32_t k = coloring.chunk[i];
      for (std::int32_t e = coloring.chunk_begin(k); e < coloring.chunk_end(k); ++e) {
        ++visits[e];
        for (int j = 0; j < 3; ++j) {
          std::int32_t& o = owner[conn[3 * e + j]];
          EXPECT_TRUE(o == -1 || o == k) << "colour " << c << ": chunks " << o << " and " << k
                                         << " share node " << conn[3 * e + j];
          o = k;
        }
      }
    }
  }
  for (std::int32_t e = 0; e < num_elements; ++e) EXPECT_EQ(visits[e], 1) << "element " << e;
}

TEST(Coloring, ElementsOfOneColourShareNoNode) {
  const Assembled a = assemble(kRectangle, true);
  expect_valid_coloring(a.coloring, a.model.conn, a.model.num_nodes());
  EXPECT_LE(a.coloring.num_colors(), 16);
}

TEST(Coloring, ChunksOfAStructuredMeshNeedFewColoursAndEachVisitsItsElementsInOrder) {
  // 200 x 200 cells, two triangles each: 80,000 elements in chunks of 80 / 512 = 156.
  const int n = 200;
  std::vector<std::int32_t> conn;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::int32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      conn.insert(conn.end(), {a, b, d, a, d, c});
    }
  const ElementColoring coloring = color_elements(conn, (n + 1) * (n + 1));
  EXPECT_EQ(coloring.chunk_size, coloring_chunk_size(2 * n * n));
  EXPECT_EQ(coloring.chunk_size, 156);
  expect_valid_coloring(coloring, conn, (n + 1) * (n + 1));
  EXPECT_LE(coloring.num_colors(), 4);
  // The visiting order on one thread: colour by colour, chunks ascending, each chunk's
  // elements consecutively; on any number of threads, every element once.
  std::vector<std::int32_t> expected;
  for (std::int32_t i = 0; i < static_cast<std::int32_t>(coloring.chunk.size()); ++i)
    for (std::int32_t e = coloring.chunk_begin(coloring.chunk[i]);
         e < coloring.chunk_end(coloring.chunk[i]); ++e)
      expected.push_back(e);
  std::vector<std::int32_t> order;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    for_each_element_by_color(coloring, [&](std::int32_t e) { order.push_back(e); });
  }
  EXPECT_EQ(order, expected);
  std::vector<std::atomic<int>> visits(conn.size() / 3);
  for_each_element_by_color(coloring, [&](std::int32_t e) { ++visits[e]; });
  for (const auto& v : visits) EXPECT_EQ(v.load(), 1);
}

TEST(Coloring, ANodeSharedByTooManyElementsIsNamed) {
  // A fan of 70 triangles round node 0: every element touches it.
  std::vector<std::int32_t> conn;
  for (std::int32_t i = 0; i < 70; ++i) conn.insert(conn.end(), {0, 1 + i, 2 + i});
  try {
    color_elements(conn, 72);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("element 63"), std::string::npos) << e.what();
  }
}

TEST(Layout, PatternIsUpperTriangularSortedWithDiagonal) {
  const Assembled a = assemble(kRectangle, false);
  const SparsityPattern& p = a.layout.pattern;
  for (std::int32_t j = 0; j < p.n; ++j) {
    ASSERT_LT(p.col_ptr[j], p.col_ptr[j + 1]);
    for (std::int32_t q = p.col_ptr[j]; q + 1 < p.col_ptr[j + 1]; ++q)
      EXPECT_LT(p.row_idx[q], p.row_idx[q + 1]);
    EXPECT_EQ(p.row_idx[a.layout.diagonal[j]], j);
  }
}

TEST(Layout, ScatterMapSendsEachElementEntryToItsRowAndColumn) {
  // Every entry (a, b), a <= b, of every element: -1 exactly when a dof is prescribed, else
  // the value index whose row is the smaller equation, inside the larger one's column. Also
  // with contact-like triples (a node and a far edge) appended to the elements, and rollers
  // (only x or only y prescribed) scattered over the mesh.
  Assembled a = assemble(kRectangle, false);
  std::int32_t next = 0;
  for (std::size_t d = 0; d < a.equation.size(); ++d) {
    const std::size_t n = d / 2;
    const bool roller = d % 2 == 0 ? n % 3 == 1 : n % 5 == 2;
    a.equation[d] = a.equation[d] < 0 || roller ? -1 : next++;
  }
  std::vector<std::int32_t> conn = a.model.conn;
  const std::int32_t last = a.model.num_nodes() - 1;
  conn.insert(conn.end(), {last, 0, 1, 2, last, last - 1});
  const StiffnessLayout layout = build_stiffness_layout(conn, a.model.num_nodes(), a.equation);
  const SparsityPattern& p = layout.pattern;
  EXPECT_TRUE(layout.neighbours.node.empty());
  const auto num_elements = static_cast<std::int32_t>(conn.size() / 3);
  int checked = 0;
  for (std::int32_t e = 0; e < num_elements; ++e) {
    const std::int32_t* to = &layout.scatter[static_cast<std::size_t>(e) * kElementUpperEntries];
    for (int i = 0; i < 6; ++i)
      for (int j = i; j < 6; ++j, ++to) {
        const std::int32_t ei = a.equation[2 * conn[3 * e + i / 2] + i % 2];
        const std::int32_t ej = a.equation[2 * conn[3 * e + j / 2] + j % 2];
        if (ei < 0 || ej < 0) {
          EXPECT_EQ(*to, -1);
          continue;
        }
        const std::int32_t col = std::max(ei, ej);
        ASSERT_GE(*to, p.col_ptr[col]) << "element " << e << " entry " << i << "," << j;
        ASSERT_LT(*to, p.col_ptr[col + 1]) << "element " << e << " entry " << i << "," << j;
        EXPECT_EQ(p.row_idx[*to], std::min(ei, ej)) << "element " << e;
        ++checked;
      }
  }
  EXPECT_GT(checked, 10 * a.model.num_elements());
}

TEST(Assembly, FreeStiffnessHasExactlyThreeRigidModes) {
  // K of an unconstrained body is symmetric positive semi-definite with the 3 rigid-body
  // modes (2 translations, 1 rotation) as its null space: K r = 0 to round-off.
  const Assembled a = assemble(kRectangle, true);
  const Eigen::MatrixXd k = dense(a.layout.pattern, a.values);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(k);
  const double largest = eig.eigenvalues().maxCoeff();
  EXPECT_LT(std::abs(eig.eigenvalues()(2)), 1e-10 * largest);
  EXPECT_GT(eig.eigenvalues()(3), 1e-8 * largest);
  const auto n = a.model.num_nodes();
  Eigen::VectorXd rotation(2 * n);
  for (std::int32_t i = 0; i < n; ++i) {
    rotation(2 * i) = -a.model.X[2 * i + 1];
    rotation(2 * i + 1) = a.model.X[2 * i];
  }
  EXPECT_LT((k * rotation).norm(), 1e-10 * largest * rotation.norm());
}

TEST(Assembly, ConstrainedStiffnessIsSymmetricPositiveDefinite) {
  const Assembled a = assemble(kRectangle, false);
  const Eigen::MatrixXd k = dense(a.layout.pattern, a.values);
  EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(k).info(), Eigen::Success);
}

TEST(Assembly, MassCoefficientAddsLumpedMassToTheDiagonal) {
  const Assembled a = assemble(kRectangle, true, 0.0);
  const Assembled b = assemble(kRectangle, true, 4.0);
  // Off-diagonal values are untouched; each diagonal gains 4 m_node.
  double added = 0.0, diagonal_scale = 0.0;
  for (std::size_t q = 0; q < a.values.size(); ++q) added += b.values[q] - a.values[q];
  for (const std::int32_t q : a.layout.diagonal) diagonal_scale += std::abs(a.values[q]);
  double mass = 0.0;
  for (const double m : a.model.node_mass) mass += m;
  // Total mass rho t A = 2500 * 1 * 2 per direction; two directions times the coefficient.
  EXPECT_NEAR(mass, 2500.0 * 2.0, 1e-9);
  EXPECT_NEAR(added, 4.0 * 2.0 * mass, 1e-14 * diagonal_scale);
}

TEST(Assembly, InternalForceEqualsStiffnessTimesDisplacement) {
  const Assembled a = assemble(kRectangle, true);
  const Eigen::MatrixXd k = dense(a.layout.pattern, a.values);
  Eigen::VectorXd u = Eigen::VectorXd::Random(static_cast<Eigen::Index>(a.model.X.size())) * 1e-4;
  std::vector<double> uu(u.data(), u.data() + u.size()), strain(3 * a.model.num_elements()),
      stress(3 * a.model.num_elements()), f(a.model.X.size());
  compute_internal_force(a.model, a.coloring, uu, strain, stress, f);
  const Eigen::VectorXd ku = k * u;
  for (Eigen::Index i = 0; i < u.size(); ++i)
    EXPECT_NEAR(f[i], ku(i), 1e-9 * ku.cwiseAbs().maxCoeff());
  // Clapeyron: 1/2 u.K.u equals the summed element strain energy.
  EXPECT_NEAR(strain_energy(a.model, strain, stress), 0.5 * u.dot(ku), 1e-10 * 0.5 * u.dot(ku));
}

TEST(Assembly, BitwiseIdenticalForOneAndTwoThreads) {
  std::vector<double> one, two, f_one, f_two;
  const std::string fine = kRectangle + "\n";
  auto run = [&](int threads, std::vector<double>& values, std::vector<double>& f) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    test::TempDir dir;
    const Scene scene = test::scene_from_text(fine, dir.path(), {"mesh.element_size=0.02"});
    Model model = build_scene_model(scene);
    std::vector<std::int32_t> equation(model.X.size());
    for (std::size_t d = 0; d < equation.size(); ++d) equation[d] = static_cast<std::int32_t>(d);
    const ElementColoring coloring = color_elements(model.conn, model.num_nodes());
    const StiffnessLayout layout = build_stiffness_layout(model.conn, model.num_nodes(), equation);
    values.assign(static_cast<std::size_t>(layout.pattern.nnz()), 0.0);
    assemble_stiffness(model, coloring, layout, equation, 3.0, values);
    std::vector<double> u(model.X.size()), strain(3 * model.num_elements()), stress(strain.size());
    for (std::size_t d = 0; d < u.size(); ++d)
      u[d] = 1e-5 * std::sin(0.37 * static_cast<double>(d));
    f.assign(model.X.size(), 0.0);
    compute_internal_force(model, coloring, u, strain, stress, f);
  };
  run(1, one, f_one);
  run(2, two, f_two);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_GT(one.size(), 10000u);
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(f_one.data(), f_two.data(), f_one.size() * sizeof(double)), 0);
}

// The solve check's residual r = b - A x from the upper triangle (engine/assembly/
// sparsity_pattern.hpp): equal to the dense product to round-off, and bit for bit to the
// entry-by-entry form it replaced (the check's decisions must not move with its speed).
TEST(Assembly, SymmetricResidualIsTheEntryByEntryResidual) {
  const Assembled a = assemble(kRectangle, false);
  const SparsityPattern& pattern = a.layout.pattern;
  const auto n = static_cast<std::size_t>(pattern.n);
  std::vector<double> x(n), b(n), r(n), reference(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = 1e-4 * std::sin(0.7 * static_cast<double>(i));
    b[i] = 1e5 * std::cos(0.3 * static_cast<double>(i));
  }
  symmetric_residual(pattern, a.values, x, b, r);
  reference = b;
  for (std::int32_t j = 0; j < pattern.n; ++j)
    for (std::int32_t p = pattern.col_ptr[j]; p < pattern.col_ptr[j + 1]; ++p) {
      const std::int32_t i = pattern.row_idx[p];
      reference[i] -= a.values[p] * x[j];
      if (i != j) reference[j] -= a.values[p] * x[i];
    }
  EXPECT_EQ(std::memcmp(r.data(), reference.data(), n * sizeof(double)), 0);
  const Eigen::MatrixXd k = dense(pattern, a.values);
  const Eigen::VectorXd ax = k * Eigen::Map<const Eigen::VectorXd>(x.data(), pattern.n);
  double scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) scale = std::max(scale, std::abs(b[i]) + std::abs(ax(i)));
  for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(r[i], b[i] - ax(i), 1e-12 * scale);
}

// A pass that starts from a known one (the committed state's, or the last solve's) recomputes
// only the elements a displacement change moved or a damage pass changed, and sums all of
// them: its f_int, strains and stresses must be those of a whole pass bit for bit, since the
// step loop's results do not depend on which of the two ran (both kinematics).
TEST(Assembly, APassFromAKnownOneIsBitwiseAWholePass) {
  for (const bool corotational : {false, true}) {
    test::TempDir dir;
    const Scene scene = test::scene_from_text(kRectangle, dir.path(), {"mesh.element_size=0.05"});
    Model model = build_scene_model(scene);
    const ElementColoring coloring = color_elements(model.conn, model.num_nodes());
    const auto num_elements = static_cast<std::size_t>(model.num_elements());
    std::vector<double> u(model.X.size()), strain(3 * num_elements), stress(strain.size()),
        element_force(6 * num_elements), f_known(model.X.size());
    for (std::size_t d = 0; d < u.size(); ++d)
      u[d] = 1e-3 * std::sin(0.37 * static_cast<double>(d)) + (d % 2 ? 0.02 * model.X[d - 1] : 0.0);
    compute_internal_force(model, coloring, u, strain, stress, f_known, corotational,
                           element_force);
    // The right edge moves (a platen's increment), and some elements damage.
    std::vector<double> u_next = u;
    for (std::size_t d = 0; d < u.size(); d += 2)
      if (model.X[d] > 1.999) u_next[d] += 1e-4;
    const std::vector<double> damage_before = model.damage;
    for (std::size_t e = 0; e < num_elements; e += 7) model.damage[e] = 0.3;
    std::vector<std::uint8_t> moved_nodes;
    std::vector<std::int32_t> stale, changed;
    elements_moved_between(model, u, u_next, moved_nodes, stale);
    EXPECT_FALSE(stale.empty());
    EXPECT_LT(stale.size(), num_elements / 4);
    changed_elements(model, damage_before, changed);
    stale.insert(stale.end(), changed.begin(), changed.end());
    std::sort(stale.begin(), stale.end());
    stale.erase(std::unique(stale.begin(), stale.end()), stale.end());
    refresh_element_forces(model, u_next, stale, element_force, corotational, strain, stress);
    std::vector<double> f_from_known(model.X.size());
    sum_element_forces(model, coloring, element_force, f_from_known);

    std::vector<double> whole_strain(strain.size()), whole_stress(strain.size()),
        whole_force(element_force.size()), f_whole(model.X.size());
    compute_internal_force(model, coloring, u_next, whole_strain, whole_stress, f_whole,
                           corotational, whole_force);
    const auto same = [](const std::vector<double>& a, const std::vector<double>& b) {
      return a.size() == b.size() &&
             std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
    };
    EXPECT_TRUE(same(f_from_known, f_whole)) << "corotational " << corotational;
    EXPECT_TRUE(same(strain, whole_strain)) << "corotational " << corotational;
    EXPECT_TRUE(same(stress, whole_stress)) << "corotational " << corotational;
    EXPECT_TRUE(same(element_force, whole_force)) << "corotational " << corotational;
  }
}

// A damage pass changes K by K(after) - K(before); modulus_change_terms writes it as
// added C C^T - removed C C^T (each changed element's rank-3 factor, co-rotated frame
// included), and add_modulus_change adds it to assembled values. Both must equal the
// difference of two full assemblies to round-off (1e-12 of the largest entry), with the
// left edge's dofs eliminated, on turned elements, for damage that grows and (as a retried
// step's reset does) falls.
TEST(ModulusChange, TermsAndValuesEqualTheDifferenceOfTwoAssemblies) {
  Assembled a = assemble(kRectangle, false);
  Model& model = a.model;
  model.rotation.assign(static_cast<std::size_t>(model.num_elements()), 0.0);
  for (std::int32_t e = 0; e < model.num_elements(); ++e) model.rotation[e] = 0.01 * (e % 17);
  model.damage.assign(static_cast<std::size_t>(model.num_elements()), 0.0);
  for (std::int32_t e = 0; e < model.num_elements(); e += 5) model.damage[e] = 0.3;
  std::vector<double> before_values(a.values.size());
  assemble_stiffness(model, a.coloring, a.layout, a.equation, 0.0, before_values);
  const std::vector<double> damage_before = model.damage;
  for (std::int32_t e = 0; e < model.num_elements(); e += 3) model.damage[e] = 0.9;
  for (std::int32_t e = 0; e < model.num_elements(); e += 10) model.damage[e] = 0.1;  // healed
  model.damage[1] = 1.0;  // fully broken: down to the stiffness floor
  std::vector<double> after_values(a.values.size());
  assemble_stiffness(model, a.coloring, a.layout, a.equation, 0.0, after_values);

  std::vector<std::int32_t> changed;
  changed_elements(model, damage_before, changed);
  EXPECT_GT(changed.size(), 0u);
  LowRankTerms added, removed;
  modulus_change_terms(model, a.equation, changed, damage_before, added, removed);
  EXPECT_GT(added.num_columns(), 0);
  EXPECT_EQ(added.num_columns() + removed.num_columns(), 3 * static_cast<int>(changed.size()));
  const Eigen::Index n = a.layout.pattern.n;
  auto outer = [n](const LowRankTerms& t) {
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
    for (std::int32_t j = 0; j < t.num_columns(); ++j) {
      Eigen::VectorXd c = Eigen::VectorXd::Zero(n);
      for (std::int32_t q = t.col_ptr[j]; q < t.col_ptr[j + 1]; ++q)
        if (t.row[q] >= 0) c(t.row[q]) += t.value[q];
      m += c * c.transpose();
    }
    return m;
  };
  const Eigen::MatrixXd expected =
      dense(a.layout.pattern, after_values) - dense(a.layout.pattern, before_values);
  const double scale = dense(a.layout.pattern, before_values).cwiseAbs().maxCoeff();
  EXPECT_LT((outer(added) - outer(removed) - expected).cwiseAbs().maxCoeff(), 1e-12 * scale);

  std::vector<double> folded = before_values;
  add_modulus_change(model, a.layout, changed, damage_before, folded);
  EXPECT_LT((dense(a.layout.pattern, folded) - dense(a.layout.pattern, after_values))
                .cwiseAbs()
                .maxCoeff(),
            1e-12 * scale);
}

}  // namespace
}  // namespace rockdd
