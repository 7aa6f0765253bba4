#pragma once
// Symmetric sparsity pattern in compressed-column form, upper triangle only (row <= col).
#include <cstdint>
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

}  // namespace rockdd
