// Disjoint sets of 0 .. n-1 with path halving: facets of one closed component,
// collinear curves of one line, vertices of one connected component, faces of
// one region. No CGAL.
#pragma once
#include <atomic>
#include <cstddef>
#include <numeric>
#include <utility>
#include <vector>

namespace vismap {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(int a, int b) { parent[find(a)] = find(b); }
};

// Disjoint sets joined on several threads at once (path halving, compare and
// swap). A root is only ever linked under a smaller one, so each set's root is
// its least member: the roots are the same whatever the order of the joins.
class ConcurrentUnionFind {
 public:
  explicit ConcurrentUnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int x) {
    for (;;) {
      int p = at(x).load(std::memory_order_relaxed);
      if (p == x) return x;
      const int up = at(p).load(std::memory_order_relaxed);
      if (up != p) at(x).compare_exchange_weak(p, up, std::memory_order_relaxed);   // (failed: moved on already)
      x = up;
    }
  }
  void join(int a, int b) {
    for (;;) {
      a = find(a);
      b = find(b);
      if (a == b) return;
      if (a < b) std::swap(a, b);
      int root = a;
      if (at(a).compare_exchange_strong(root, b, std::memory_order_relaxed)) return;
    }
  }

 private:
  std::atomic_ref<int> at(int x) { return std::atomic_ref<int>(parent_[static_cast<std::size_t>(x)]); }
  std::vector<int> parent_;
};

}  // namespace vismap
