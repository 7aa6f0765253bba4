#pragma once
// Disjoint sets (union-find) over 0..n-1, with path halving: how elements or nodes are grouped
// into parts (blocks, the parts a restraint holds, what joins a load path). The smaller root
// leads, so a set's representative is its lowest member whatever order the joins come in, and
// parts numbered by it are the same for any thread count.
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace rockdd {

/// Union-find over the integers 0..n-1; each set is represented by its lowest member.
class DisjointSets {
 public:
  DisjointSets() = default;
  explicit DisjointSets(std::size_t n) { reset(n); }

  /// n singletons, keeping the storage already held.
  void reset(std::size_t n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), std::int32_t{0});
  }
  /// The representative of x's set: its lowest member.
  std::int32_t find(std::int32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  /// Merges the sets of a and b.
  void join(std::int32_t a, std::int32_t b) {
    a = find(a);
    b = find(b);
    if (a < b)
      parent_[b] = a;
    else if (b < a)
      parent_[a] = b;
  }

 private:
  std::vector<std::int32_t> parent_;
};

}  // namespace rockdd
