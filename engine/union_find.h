// Disjoint sets of 0 .. n-1 with path halving: facets of one closed component,
// collinear curves of one line, vertices of one connected component, faces of
// one region. No CGAL.
#pragma once
#include <cstddef>
#include <numeric>
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

}  // namespace vismap
