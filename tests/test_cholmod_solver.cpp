// CholmodSolver: factorize and solve, and low-rank updates of the factor (A +/- C C^T)
// checked against fresh factorizations of the modified matrix; the fill-reducing orderings of
// the node graph (engine/solver/fill_reducing_ordering). No test times anything.
#include "engine/solver/cholmod_solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "engine/common/errors.hpp"
#include "engine/solver/fill_reducing_ordering.hpp"

namespace rockdd {
namespace {

/// A symmetric matrix kept as a map of its upper triangle, turned into a pattern + values.
struct SymmetricMatrix {
  std::int32_t n = 0;
  std::map<std::pair<std::int32_t, std::int32_t>, double> upper;  // (row, col), row <= col

  void add(std::int32_t i, std::int32_t j, double v) {
    if (i > j) std::swap(i, j);
    upper[{i, j}] += v;
  }
  /// += s * c c^T for a sparse column (rows < 0 skipped).
  void add_outer(const std::vector<std::int32_t>& rows, const std::vector<double>& values,
                 double s) {
    for (std::size_t a = 0; a < rows.size(); ++a)
      for (std::size_t b = 0; b < rows.size(); ++b) {
        if (rows[a] < 0 || rows[b] < 0 || rows[a] > rows[b]) continue;
        // (a, b) and (b, a) land on the same stored entry when the rows differ.
        upper[{rows[a], rows[b]}] += s * values[a] * values[b];
      }
  }
  /// Pattern and values in pattern order.
  void compress(SparsityPattern& pattern, std::vector<double>& values) const {
    std::vector<std::vector<std::pair<std::int32_t, double>>> columns(n);
    for (const auto& [ij, v] : upper) columns[ij.second].emplace_back(ij.first, v);
    pattern.n = n;
    pattern.col_ptr.assign(1, 0);
    pattern.row_idx.clear();
    values.clear();
    for (auto& col : columns) {
      std::sort(col.begin(), col.end());
      for (const auto& [row, v] : col) {
        pattern.row_idx.push_back(row);
        values.push_back(v);
      }
      pattern.col_ptr.push_back(static_cast<std::int32_t>(pattern.row_idx.size()));
    }
  }
  std::vector<double> multiply(const std::vector<double>& x) const {
    std::vector<double> y(x.size(), 0.0);
    for (const auto& [ij, v] : upper) {
      y[ij.first] += v * x[ij.second];
      if (ij.first != ij.second) y[ij.second] += v * x[ij.first];
    }
    return y;
  }
};

/// A stiffness-like SPD matrix over a grid of nx x ny nodes with 2 dofs each: every triangle
/// of the grid adds random rank-1 terms over its 6 dofs, plus a diagonal shift.
SymmetricMatrix grid_matrix(int nx, int ny, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SymmetricMatrix a;
  a.n = 2 * nx * ny;
  auto node = [&](int i, int j) { return j * nx + i; };
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i)
      for (const auto& tri : {std::array{node(i, j), node(i + 1, j), node(i + 1, j + 1)},
                              std::array{node(i, j), node(i + 1, j + 1), node(i, j + 1)}}) {
        std::vector<std::int32_t> rows;
        for (const int n : tri) rows.insert(rows.end(), {2 * n, 2 * n + 1});
        for (int r = 0; r < 3; ++r) {
          std::vector<double> v(6);
          for (double& x : v) x = u(rng);
          a.add_outer(rows, v, 1.0);
        }
      }
  for (std::int32_t i = 0; i < a.n; ++i) a.add(i, i, 0.5);
  return a;
}

/// A contact-like column: 6 random values over the dofs of 3 nodes.
std::pair<std::vector<std::int32_t>, std::vector<double>> random_column(std::int32_t num_nodes,
                                                                        int nx, std::mt19937& rng,
                                                                        double scale = 1.0) {
  std::uniform_int_distribution<std::int32_t> pick(0, num_nodes - 1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::int32_t p = pick(rng);
  if (p % nx == nx - 1) --p;
  if (p + nx >= num_nodes) p -= nx;
  const std::int32_t nodes[3] = {p, p + 1, p + 1 + nx};  // a triangle of the grid
  std::pair<std::vector<std::int32_t>, std::vector<double>> col;
  for (const std::int32_t n : nodes)
    for (int c = 0; c < 2; ++c) {
      col.first.push_back(2 * n + c);
      col.second.push_back(scale * u(rng));
    }
  return col;
}

double relative_difference(const std::vector<double>& x, const std::vector<double>& y) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    num += (x[i] - y[i]) * (x[i] - y[i]);
    den += y[i] * y[i];
  }
  return std::sqrt(num / den);
}

/// x = A^{-1} b by a fresh analysis and factorization of `a`.
std::vector<double> fresh_solve(const SymmetricMatrix& a, const std::vector<double>& b) {
  SparsityPattern pattern;
  std::vector<double> values;
  a.compress(pattern, values);
  CholmodSolver solver;
  solver.analyze(pattern);
  solver.factorize(values.data());
  std::vector<double> x(b.size());
  solver.solve(b.data(), x.data());
  return x;
}

std::vector<double> solve(CholmodSolver& solver, const std::vector<double>& b) {
  std::vector<double> x(b.size());
  solver.solve(b.data(), x.data());
  return x;
}

std::vector<double> random_vector(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> b(n);
  for (double& v : b) v = u(rng);
  return b;
}

/// A factorized solver for `a` (pattern of `a` only).
void factorize(CholmodSolver& solver, const SymmetricMatrix& a) {
  SparsityPattern pattern;
  std::vector<double> values;
  a.compress(pattern, values);
  solver.analyze(pattern);
  solver.factorize(values.data());
}

TEST(CholmodSolver, SolvesAFactorizedSystem) {
  std::mt19937 rng(1);
  const SymmetricMatrix a = grid_matrix(12, 10, rng);
  CholmodSolver solver;
  EXPECT_FALSE(solver.analyzed());
  factorize(solver, a);
  EXPECT_TRUE(solver.analyzed());
  EXPECT_TRUE(solver.supernodal());
  const std::vector<double> b = random_vector(static_cast<std::size_t>(a.n), rng);
  const std::vector<double> x = solve(solver, b);
  EXPECT_LT(relative_difference(a.multiply(x), b), 1e-12);
  EXPECT_EQ(solver.stats().analyses, 1);
  EXPECT_EQ(solver.stats().factorizations, 1);
  EXPECT_EQ(solver.stats().updates, 0);
}

TEST(CholmodSolver, SeveralColumnsAtOnceAreEachColumnSolvedAlone) {
  // solve(b, x, k): k right-hand sides, one after the other, in one pass over the factor. Each
  // column's solution satisfies A x = b to 1e-12 and equals the one-column solve of the same b
  // to 1e-14 (BLAS-3 sums in another order); an updated (simplicial) factor too.
  std::mt19937 rng(3);
  const SymmetricMatrix a = grid_matrix(12, 10, rng);
  CholmodSolver solver;
  factorize(solver, a);
  const auto n = static_cast<std::size_t>(a.n);
  constexpr int kColumns = 5;
  for (const bool updated : {false, true}) {
    SymmetricMatrix modified = a;
    if (updated) {
      LowRankTerms terms;
      const std::vector<std::int32_t> rows = {3, 17, 40};
      const std::vector<double> values = {0.5, -1.0, 2.0};
      terms.add_column(rows, values);
      solver.update(terms, true);
      modified.add_outer(rows, values, 1.0);
      EXPECT_FALSE(solver.supernodal());
    }
    std::vector<double> b(n * kColumns), x(n * kColumns);
    for (double& v : b) v = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
    solver.solve(b.data(), x.data(), kColumns);
    for (int j = 0; j < kColumns; ++j) {
      const std::vector<double> bj(b.begin() + j * a.n, b.begin() + (j + 1) * a.n);
      const std::vector<double> xj(x.begin() + j * a.n, x.begin() + (j + 1) * a.n);
      EXPECT_LT(relative_difference(modified.multiply(xj), bj), 1e-12) << "column " << j;
      EXPECT_LT(relative_difference(solve(solver, bj), xj), 1e-14) << "column " << j;
    }
  }
  EXPECT_THROW(solver.solve(nullptr, nullptr, 0), std::invalid_argument);
}

/// `a` without the equations that `drop` selects, the others renumbered in order: a node
/// that loses one dof keeps a single equation, as a node with a prescribed dof does.
template <class Drop>
SymmetricMatrix without_equations(const SymmetricMatrix& a, Drop drop) {
  std::vector<std::int32_t> renumber(static_cast<std::size_t>(a.n), -1);
  SymmetricMatrix b;
  for (std::int32_t i = 0; i < a.n; ++i)
    if (!drop(i)) renumber[i] = b.n++;
  for (const auto& [ij, v] : a.upper)
    if (renumber[ij.first] >= 0 && renumber[ij.second] >= 0)
      b.add(renumber[ij.first], renumber[ij.second], v);
  return b;
}

/// ||A x - b|| / ||b||.
double relative_residual(const SymmetricMatrix& a, const std::vector<double>& x,
                         const std::vector<double>& b) {
  return relative_difference(a.multiply(x), b);
}

TEST(FillReducingOrdering, GroupsAreTheFreeDofsOfEachNode) {
  std::mt19937 rng(11);
  const SymmetricMatrix full = grid_matrix(9, 7, rng);
  SparsityPattern pattern;
  std::vector<double> values;
  full.compress(pattern, values);
  std::vector<std::int32_t> start = equation_groups(pattern);
  ASSERT_EQ(start.size(), static_cast<std::size_t>(9 * 7 + 1));
  for (std::size_t g = 0; g + 1 < start.size(); ++g) EXPECT_EQ(start[g], 2 * g);

  // Every 5th dof prescribed: nodes 0, 5, 10, ... keep their y dof only, 2, 7, ... their x.
  const SymmetricMatrix reduced =
      without_equations(full, [](std::int32_t i) { return i % 5 == 0; });
  reduced.compress(pattern, values);
  start = equation_groups(pattern);
  EXPECT_EQ(start.size(), static_cast<std::size_t>(9 * 7 + 1));  // still one group per node
  EXPECT_EQ(start.back(), reduced.n);
  std::int32_t singles = 0;
  for (std::size_t g = 0; g + 1 < start.size(); ++g) singles += start[g + 1] - start[g] == 1;
  EXPECT_EQ(singles, (2 * 9 * 7 + 4) / 5);
}

TEST(FillReducingOrdering, NodeOrderingsArePermutationsKeepingEachNodesEquationsTogether) {
  std::mt19937 rng(12);
  const SymmetricMatrix a =
      without_equations(grid_matrix(20, 15, rng), [](std::int32_t i) { return i % 7 == 3; });
  SparsityPattern pattern;
  std::vector<double> values;
  a.compress(pattern, values);
  const std::vector<std::int32_t> start = equation_groups(pattern);
  std::vector<std::int32_t> group_of(static_cast<std::size_t>(a.n));
  for (std::size_t g = 0; g + 1 < start.size(); ++g)
    for (std::int32_t e = start[g]; e < start[g + 1]; ++e)
      group_of[e] = static_cast<std::int32_t>(g);
  for (const FillOrdering ordering : {FillOrdering::node_metis, FillOrdering::node_amd}) {
    SCOPED_TRACE(std::string(fill_ordering_name(ordering)));
    const std::vector<std::int32_t> perm = node_graph_ordering(pattern, ordering);
    ASSERT_EQ(perm.size(), static_cast<std::size_t>(a.n));
    std::vector<std::int32_t> sorted = perm;
    std::sort(sorted.begin(), sorted.end());
    for (std::int32_t k = 0; k < a.n; ++k) ASSERT_EQ(sorted[k], k);  // a permutation
    // Each group appears as one run, its equations in increasing order.
    for (std::int32_t k = 0; k < a.n; ++k) {
      const std::int32_t e = perm[k], g = group_of[e];
      if (e == start[g]) {
        for (std::int32_t j = 1; j < start[g + 1] - start[g]; ++j) EXPECT_EQ(perm[k + j], e + j);
      }
    }
  }
  EXPECT_THROW(node_graph_ordering(pattern, FillOrdering::cholmod), std::invalid_argument);
}

TEST(CholmodSolver, EveryOrderingSolvesTheSameSystemToRoundOff) {
  // Residual ||A x - b|| / ||b|| < 1e-12 for each ordering, and the solutions agree with
  // CHOLMOD's own ordering to 1e-10 (relative 2-norm; the matrix's condition number is
  // about 1e3, so orderings that round differently differ by far less).
  std::mt19937 rng(13);
  const SymmetricMatrix a =
      without_equations(grid_matrix(30, 25, rng), [](std::int32_t i) { return i % 11 == 4; });
  const std::vector<double> b = random_vector(static_cast<std::size_t>(a.n), rng);
  std::vector<double> reference;
  for (const FillOrdering ordering :
       {FillOrdering::cholmod, FillOrdering::cholmod_amd, FillOrdering::node_metis,
        FillOrdering::node_amd, FillOrdering::node}) {
    SCOPED_TRACE(std::string(fill_ordering_name(ordering)));
    CholmodSolver solver(ordering);
    factorize(solver, a);
    const std::vector<double> x = solve(solver, b);
    EXPECT_LT(relative_residual(a, x, b), 1e-12);
    if (reference.empty())
      reference = x;
    else
      EXPECT_LT(relative_difference(x, reference), 1e-10);
    EXPECT_GT(solver.stats().factor_nonzeros, 0.0);
    EXPECT_NE(solver.stats().ordering, FillOrdering::node);  // names the ordering it kept
  }
}

TEST(CholmodSolver, TheDissectionByCoordinatesSolvesToRoundOff) {
  // The same bounds as every other ordering above; it needs each equation's node position.
  std::mt19937 rng(17);
  const int nx = 30, ny = 25;
  const SymmetricMatrix a = grid_matrix(nx, ny, rng);
  SparsityPattern pattern;
  std::vector<double> values;
  a.compress(pattern, values);
  std::vector<double> xy;
  for (std::int32_t e = 0; e < a.n; ++e)
    xy.insert(xy.end(), {double(e / 2 % nx), double(e / 2 / nx)});
  const std::vector<double> b = random_vector(static_cast<std::size_t>(a.n), rng);
  CholmodSolver solver(FillOrdering::node_geometric);
  solver.analyze(pattern, xy);
  solver.factorize(values.data());
  const std::vector<double> x = solve(solver, b);
  EXPECT_EQ(solver.stats().ordering, FillOrdering::node_geometric);
  EXPECT_LT(relative_residual(a, x, b), 1e-12);
  EXPECT_LT(relative_difference(x, fresh_solve(a, b)), 1e-10);
  CholmodSolver blind(FillOrdering::node_geometric);
  EXPECT_THROW(blind.analyze(pattern), std::invalid_argument);  // no coordinates
}

TEST(CholmodSolver, AnalysisGivenAnEarlierOrderingIsBitwiseThatAnalysis) {
  // analyze_given(permutation() of an earlier analysis) is what a stored ordering replays:
  // the same elimination order, factor size and kept method, and bitwise the same solution,
  // for every strategy (METIS's and CHOLMOD's orderings are postordered by CHOLMOD: the given
  // one is taken as it is).
  std::mt19937 rng(29);
  const SymmetricMatrix a =
      without_equations(grid_matrix(40, 33, rng), [](std::int32_t i) { return i % 13 == 5; });
  SparsityPattern pattern;
  std::vector<double> values;
  a.compress(pattern, values);
  const std::vector<double> b = random_vector(static_cast<std::size_t>(a.n), rng);
  for (const FillOrdering ordering :
       {FillOrdering::cholmod, FillOrdering::cholmod_amd, FillOrdering::node_metis,
        FillOrdering::node_amd, FillOrdering::node}) {
    SCOPED_TRACE(std::string(fill_ordering_name(ordering)));
    CholmodSolver first(ordering);
    first.analyze(pattern);
    first.factorize(values.data());
    CholmodSolver replay(ordering);
    replay.analyze_given(pattern, first.permutation(), first.stats().ordering);
    replay.factorize(values.data());
    EXPECT_EQ(replay.permutation(), first.permutation());
    EXPECT_EQ(replay.stats().ordering, first.stats().ordering);
    EXPECT_EQ(replay.stats().factor_nonzeros, first.stats().factor_nonzeros);
    EXPECT_EQ(replay.stats().analysis_flops, first.stats().analysis_flops);
    EXPECT_EQ(solve(replay, b), solve(first, b));  // bit for bit
  }
  // A node_metis ordering is kept by the default strategy on a large enough grid: replayed
  // the same way.
  CholmodSolver metis(FillOrdering::node_metis);
  metis.analyze(pattern);
  CholmodSolver replay;
  replay.analyze_given(pattern, metis.permutation(), FillOrdering::node_metis);
  EXPECT_EQ(replay.stats().ordering, FillOrdering::node_metis);
  EXPECT_EQ(replay.permutation(), metis.permutation());
}

TEST(CholmodSolver, AGivenOrderingMustBeAPermutationOfTheEquations) {
  std::mt19937 rng(31);
  const SymmetricMatrix a = grid_matrix(6, 5, rng);
  SparsityPattern pattern;
  std::vector<double> values;
  a.compress(pattern, values);
  std::vector<std::int32_t> perm(static_cast<std::size_t>(a.n));
  for (std::int32_t k = 0; k < a.n; ++k) perm[k] = a.n - 1 - k;
  CholmodSolver solver;
  std::vector<std::int32_t> bad = perm;
  bad.pop_back();  // one short
  EXPECT_THROW(solver.analyze_given(pattern, bad, FillOrdering::node_amd), std::invalid_argument);
  bad = perm;
  bad[3] = bad[4];  // a repeat
  EXPECT_THROW(solver.analyze_given(pattern, bad, FillOrdering::node_amd), std::invalid_argument);
  bad = perm;
  bad[0] = a.n;  // out of range
  EXPECT_THROW(solver.analyze_given(pattern, bad, FillOrdering::node_amd), std::invalid_argument);
  EXPECT_FALSE(solver.analyzed());
  solver.analyze_given(pattern, perm, FillOrdering::node_amd);  // any permutation is valid
  solver.factorize(values.data());
  const std::vector<double> b = random_vector(static_cast<std::size_t>(a.n), rng);
  EXPECT_LT(relative_residual(a, solve(solver, b), b), 1e-12);
  EXPECT_EQ(solver.permutation(), perm);
}

TEST(CholmodSolver, TheOrderingKeyNamesStrategyAndLibraries) {
  const std::string key = CholmodSolver(FillOrdering::node).ordering_key();
  EXPECT_NE(key, CholmodSolver(FillOrdering::node_metis).ordering_key());
  for (const char* part : {"ordering node ", "cholmod ", "amd ", "metis ", "solver code "})
    EXPECT_NE(key.find(part), std::string::npos) << part;
  for (const FillOrdering o :
       {FillOrdering::cholmod, FillOrdering::node_metis, FillOrdering::node_amd, FillOrdering::node,
        FillOrdering::cholmod_amd, FillOrdering::node_geometric})
    EXPECT_EQ(fill_ordering_from_name(fill_ordering_name(o)), o);
  EXPECT_FALSE(fill_ordering_from_name("metis"));
}

TEST(CholmodSolver, UpdatesWorkInTheNodeOrdering) {
  std::mt19937 rng(14);
  const int nx = 16, ny = 14;
  SymmetricMatrix a = grid_matrix(nx, ny, rng);
  CholmodSolver solver(FillOrdering::node_metis);
  factorize(solver, a);
  LowRankTerms terms;
  for (int k = 0; k < 12; ++k) {
    const auto [rows, values] = random_column(nx * ny, nx, rng);
    terms.add_column(rows, values);
    a.add_outer(rows, values, 1.0);
  }
  solver.update(terms, true);
  const std::vector<double> b = random_vector(static_cast<std::size_t>(a.n), rng);
  const std::vector<double> x = solve(solver, b);
  EXPECT_LT(relative_residual(a, x, b), 1e-10);
  EXPECT_LT(relative_difference(x, fresh_solve(a, b)), 1e-10);
}

TEST(CholmodSolver, UpdateMatchesAFreshFactorizationOfTheModifiedMatrix) {
  std::mt19937 rng(2);
  const int nx = 15, ny = 15;
  const SymmetricMatrix a = grid_matrix(nx, ny, rng);
  CholmodSolver solver;
  factorize(solver, a);
  LowRankTerms terms;
  SymmetricMatrix modified = a;
  for (int k = 0; k < 5; ++k) {
    const auto [rows, values] = random_column(nx * ny, nx, rng, 3.0);
    terms.add_column(rows, values);
    modified.add_outer(rows, values, 1.0);
  }
  solver.update(terms, true);
  EXPECT_FALSE(solver.supernodal());
  const std::vector<double> b = random_vector(static_cast<std::size_t>(a.n), rng);
  const std::vector<double> x = solve(solver, b);
  EXPECT_LT(relative_difference(x, fresh_solve(modified, b)), 1e-10);
  EXPECT_LT(relative_difference(modified.multiply(x), b), 1e-10);
  // Against the unmodified matrix the solution is clearly different.
  EXPECT_GT(relative_difference(x, fresh_solve(a, b)), 1e-3);
}

TEST(CholmodSolver, DowndateRestoresTheOriginalMatrix) {
  std::mt19937 rng(3);
  const int nx = 14, ny = 11;
  const SymmetricMatrix a = grid_matrix(nx, ny, rng);
  CholmodSolver solver;
  factorize(solver, a);
  LowRankTerms terms;
  for (int k = 0; k < 12; ++k) {
    const auto [rows, values] = random_column(nx * ny, nx, rng, 2.0);
    terms.add_column(rows, values);
  }
  const std::vector<double> b = random_vector(static_cast<std::size_t>(a.n), rng);
  const std::vector<double> before = solve(solver, b);
  solver.update(terms, true);
  solver.update(terms, false);
  const std::vector<double> after = solve(solver, b);
  EXPECT_LT(relative_difference(after, before), 1e-10);
  EXPECT_LT(relative_difference(a.multiply(after), b), 1e-10);
}

TEST(CholmodSolver, MixedUpdatesTrackTheModifiedMatrix) {
  std::mt19937 rng(4);
  const int nx = 20, ny = 16;
  SymmetricMatrix a = grid_matrix(nx, ny, rng);
  CholmodSolver solver;
  factorize(solver, a);
  // Springs that are switched on and off, as contacts close and open.
  std::vector<std::pair<std::vector<std::int32_t>, std::vector<double>>> springs;
  for (int s = 0; s < 40; ++s) springs.push_back(random_column(nx * ny, nx, rng, 1.5));
  std::vector<bool> on(springs.size(), false);
  std::bernoulli_distribution flip(0.2);
  std::int64_t columns = 0;
  int calls = 0;
  for (int round = 0; round < 8; ++round) {
    LowRankTerms close, open;
    for (std::size_t s = 0; s < springs.size(); ++s) {
      if (!flip(rng)) continue;
      (on[s] ? open : close).add_column(springs[s].first, springs[s].second);
      a.add_outer(springs[s].first, springs[s].second, on[s] ? -1.0 : 1.0);
      on[s] = !on[s];
    }
    for (const auto& [terms, add] : {std::pair{&close, true}, std::pair{&open, false}}) {
      if (terms->num_columns() == 0) continue;
      solver.update(*terms, add);
      columns += terms->num_columns();
      ++calls;
    }
    const std::vector<double> b = random_vector(static_cast<std::size_t>(a.n), rng);
    const std::vector<double> x = solve(solver, b);
    EXPECT_LT(relative_difference(x, fresh_solve(a, b)), 1e-10) << "round " << round;
    EXPECT_LT(relative_difference(a.multiply(x), b), 1e-10) << "round " << round;
  }
  EXPECT_EQ(solver.stats().analyses, 1);
  EXPECT_EQ(solver.stats().factorizations, 1);
  EXPECT_EQ(solver.stats().updates, calls);
  EXPECT_EQ(solver.stats().updated_columns, columns);
  EXPECT_EQ(solver.stats().simplicial_conversions, 1);

  // A refactorization after updates is supernodal again, with the same analysis (the
  // springs lie on triangles of the grid: A's pattern has not changed).
  SparsityPattern pattern;
  std::vector<double> values;
  a.compress(pattern, values);
  solver.factorize(values.data());
  EXPECT_TRUE(solver.supernodal());
  const std::vector<double> b = random_vector(static_cast<std::size_t>(a.n), rng);
  EXPECT_LT(relative_difference(a.multiply(solve(solver, b)), b), 1e-10);
  EXPECT_EQ(solver.stats().analyses, 1);
  EXPECT_EQ(solver.stats().factorizations, 2);

  // And it can be updated again.
  LowRankTerms terms;
  const auto [rows, vals] = random_column(nx * ny, nx, rng, 1.0);
  terms.add_column(rows, vals);
  a.add_outer(rows, vals, 1.0);
  solver.update(terms, true);
  EXPECT_LT(relative_difference(a.multiply(solve(solver, b)), b), 1e-10);
  EXPECT_EQ(solver.stats().simplicial_conversions, 2);
}

TEST(CholmodSolver, PrescribedRowsAreSkippedAndRepeatedRowsAdd) {
  std::mt19937 rng(5);
  const int nx = 9, ny = 9;
  const SymmetricMatrix a = grid_matrix(nx, ny, rng);
  CholmodSolver solver;
  factorize(solver, a);
  LowRankTerms terms;
  // Column 1: a prescribed dof (-1) among free ones. Column 2: row 7 given twice.
  terms.add_column(std::vector<std::int32_t>{4, -1, 5, 30},
                   std::vector<double>{1.0, 9.0, -2.0, 0.5});
  terms.add_column(std::vector<std::int32_t>{7, 20, 7}, std::vector<double>{0.5, 1.0, 1.5});
  SymmetricMatrix modified = a;
  modified.add_outer({4, 5, 30}, {1.0, -2.0, 0.5}, 1.0);
  modified.add_outer({7, 20}, {2.0, 1.0}, 1.0);
  solver.update(terms, true);
  const std::vector<double> b = random_vector(static_cast<std::size_t>(a.n), rng);
  EXPECT_LT(relative_difference(solve(solver, b), fresh_solve(modified, b)), 1e-10);

  // Only prescribed rows: nothing to do, the factor stays as it was.
  CholmodSolver other;
  factorize(other, a);
  LowRankTerms none;
  none.add_column(std::vector<std::int32_t>{-1, -1}, std::vector<double>{1.0, 2.0});
  other.update(none, true);
  EXPECT_TRUE(other.supernodal());
  EXPECT_EQ(other.stats().updates, 0);
}

TEST(CholmodSolver, UpdateOutsideThePatternOfTheFactor) {
  // C couples dofs that A does not: the factor's pattern grows.
  std::mt19937 rng(6);
  const int nx = 10, ny = 10;
  const SymmetricMatrix a = grid_matrix(nx, ny, rng);
  CholmodSolver solver;
  factorize(solver, a);
  LowRankTerms terms;
  const std::vector<std::int32_t> rows{0, 1, 2 * 99, 2 * 99 + 1, 2 * 50};
  const std::vector<double> values{1.0, -1.0, 2.0, 0.5, 1.5};
  terms.add_column(rows, values);
  SymmetricMatrix modified = a;
  modified.add_outer(rows, values, 1.0);
  solver.update(terms, true);
  const std::vector<double> b = random_vector(static_cast<std::size_t>(a.n), rng);
  const std::vector<double> x = solve(solver, b);
  EXPECT_LT(relative_difference(modified.multiply(x), b), 1e-10);
  solver.update(terms, false);
  EXPECT_LT(relative_difference(a.multiply(solve(solver, b)), b), 1e-10);
}

TEST(CholmodSolver, DowndateThatLosesDefinitenessThrows) {
  // A = I (n = 4) minus 4 e_2 e_2^T is indefinite.
  SymmetricMatrix a;
  a.n = 4;
  for (std::int32_t i = 0; i < 4; ++i) a.add(i, i, 1.0);
  a.add(1, 2, 0.1);
  CholmodSolver solver;
  factorize(solver, a);
  LowRankTerms terms;
  terms.add_column(std::vector<std::int32_t>{2}, std::vector<double>{2.0});
  EXPECT_THROW(solver.update(terms, false), RunFailure);
  std::vector<double> b(4, 1.0), x(4);
  EXPECT_THROW(solver.solve(b.data(), x.data()), std::logic_error);
  // A new factorization makes the solver usable again.
  SparsityPattern pattern;
  std::vector<double> values;
  a.compress(pattern, values);
  solver.factorize(values.data());
  solver.solve(b.data(), x.data());
  EXPECT_LT(relative_difference(a.multiply(x), b), 1e-14);
}

TEST(CholmodSolver, UpdateOrRefactorEstimate) {
  std::mt19937 rng(7);
  const int nx = 12, ny = 12;
  const SymmetricMatrix a = grid_matrix(nx, ny, rng);
  CholmodSolver solver;
  EXPECT_FALSE(solver.update_expected_faster(1));  // nothing to update yet
  factorize(solver, a);
  EXPECT_TRUE(solver.update_expected_faster(0));
  EXPECT_FALSE(solver.update_expected_faster(1'000'000'000));
  LowRankTerms terms;
  const auto [rows, values] = random_column(nx * ny, nx, rng);
  terms.add_column(rows, values);
  solver.update(terms, true);  // now timed: seconds per column measured
  EXPECT_TRUE(solver.update_expected_faster(0));
  EXPECT_FALSE(solver.update_expected_faster(1'000'000'000));
  EXPECT_GT(solver.stats().last_update_seconds, 0.0);
}

TEST(CholmodSolver, MisuseIsRejected) {
  CholmodSolver solver;
  LowRankTerms terms;
  terms.add_column(std::vector<std::int32_t>{0}, std::vector<double>{1.0});
  EXPECT_THROW(solver.update(terms, true), std::logic_error);
  EXPECT_THROW(solver.factorize(nullptr), std::logic_error);
  SymmetricMatrix a;
  a.n = 3;
  for (std::int32_t i = 0; i < 3; ++i) a.add(i, i, 2.0);
  factorize(solver, a);
  LowRankTerms out_of_range;
  out_of_range.add_column(std::vector<std::int32_t>{3}, std::vector<double>{1.0});
  EXPECT_THROW(solver.update(out_of_range, true), std::invalid_argument);
  EXPECT_THROW(terms.add_column(std::vector<std::int32_t>{0, 1}, std::vector<double>{1.0}),
               std::invalid_argument);
  LowRankTerms broken = terms;
  broken.col_ptr.back() = 5;  // past the entries
  EXPECT_THROW(solver.update(broken, true), std::invalid_argument);
}

}  // namespace
}  // namespace rockdd
