#pragma once
// Symmetric sparsity pattern in compressed-column form, upper triangle only (row <= col).
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace rockdd {

/// Upper triangle of a symmetric n x n matrix, CSC, rows sorted within each column,
/// diagonal present in every column. Values live elsewhere, in the same order as row_idx.
struct SparsityPattern {
  std::int32_t n = 0;
  std::vector<std::int32_t> col_ptr;  // n + 1
  std::vector<std::int32_t> row_idx;  // col_ptr[n]
  std::int64_t nnz() const { return col_ptr.empty() ? 0 : col_ptr.back(); }
};

/// r = b - A x for the symmetric A held as `pattern`'s upper triangle with `values`.
inline void symmetric_residual(const SparsityPattern& pattern, std::span<const double> values,
                               std::span<const double> x, std::span<const double> b,
                               std::span<double> r) {
  std::copy(b.begin(), b.end(), r.begin());
  for (std::int32_t j = 0; j < pattern.n; ++j) {
    // Each column ends with its diagonal. Column j's own terms go to r[j] one by one in the
    // column's order, diagonal last, held in a register meanwhile (no other row of the column
    // is j): the same operations in the same order as entry by entry, without a branch.
    const std::int32_t diagonal = pattern.col_ptr[j + 1] - 1;
    const double xj = x[j];
    double rj = r[j];
    for (std::int32_t p = pattern.col_ptr[j]; p < diagonal; ++p) {
      const std::int32_t i = pattern.row_idx[p];
      const double v = values[static_cast<std::size_t>(p)];
      r[i] -= v * xj;
      rj -= v * x[i];
    }
    r[j] = rj - values[static_cast<std::size_t>(diagonal)] * xj;
  }
}

}  // namespace rockdd
