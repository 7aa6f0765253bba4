#pragma once
// A low-rank change of the global stiffness, C C^T, as the columns of C: what a damage pass
// or a switch of contact springs changes, for the factor to absorb by an update.
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

namespace rockdd {

/// The columns c_1..c_k of a low-rank term C, each a sparse vector in the solver's equation
/// numbering (the rows of the pattern), stored by columns. A contact spring k g g^T over the
/// contact's 6 dofs is one column sqrt(k) g. Rows below zero (prescribed dofs, whose equation
/// is -1) are skipped; repeated rows in a column add up.
struct LowRankTerms {
  std::vector<std::int32_t> col_ptr{0};  // k + 1
  std::vector<std::int32_t> row;         // equation of each entry
  std::vector<double> value;

  /// Appends the column sum_i values[i] e_{rows[i]}.
  void add_column(std::span<const std::int32_t> rows, std::span<const double> values) {
    if (rows.size() != values.size())
      throw std::invalid_argument("LowRankTerms::add_column: rows and values differ in size");
    row.insert(row.end(), rows.begin(), rows.end());
    value.insert(value.end(), values.begin(), values.end());
    col_ptr.push_back(static_cast<std::int32_t>(row.size()));
  }
  void clear() {
    col_ptr.assign(1, 0);
    row.clear();
    value.clear();
  }
  std::int32_t num_columns() const { return static_cast<std::int32_t>(col_ptr.size()) - 1; }
};

}  // namespace rockdd
