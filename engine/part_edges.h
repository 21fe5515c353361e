// Which facet edge each edge of a fragment lies on, kept as fragments are cut
// (Newell's depth sort, the BSP tree): the overlay then knows without arithmetic
// that a curve on that facet edge lies on the fragment's edge's line, the zero
// that every piece of a facet's own edge would otherwise ask of exact numbers.
// No CGAL type: the BSP tree keeps them too.
#pragma once
#include <cstdint>
#include <vector>

namespace vismap::engine {

// The polygon edges a point of a polygon's part lies on, as bits (edge k: the
// edge from corner k to corner k + 1): its corner k lies on edges k - 1 and k,
// a point cut from edge k on edge k alone. (Edges from the 64th on have no bit:
// what lies on them is not known, which is always safe.)
inline std::uint64_t edge_bit(std::size_t k) { return k < 64 ? std::uint64_t(1) << k : 0; }
inline std::uint64_t on_corner(std::size_t k, std::size_t n) { return edge_bit(k) | edge_bit((k + n - 1) % n); }
inline std::uint64_t on_edge(std::size_t k) { return edge_bit(k); }

// The edges of a part of a convex polygon whose corners lie on the polygon's
// edges `on` (bits, as above): the part's edge from corner i to i + 1 lies on the
// polygon's edge j where both ends do (convex: the segment between them is then
// a piece of edge j), its label labels[j]; else -1 (it lies on the cut).
inline std::vector<int> part_edges(const std::vector<std::uint64_t>& on, const std::vector<int>& labels) {
  const std::size_t n = on.size();
  std::vector<int> out(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t both = on[i] & on[(i + 1) % n];
    if (both) out[i] = labels[static_cast<std::size_t>(__builtin_ctzll(both))];
  }
  return out;
}

// `labels` of a polygon's edges after its corners are reversed (the edge from
// new corner i to i + 1 was the edge from old corner n - 2 - i to n - 1 - i).
inline std::vector<int> reversed_edges(const std::vector<int>& labels) {
  const std::size_t n = labels.size();
  std::vector<int> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = labels[(2 * n - 2 - i) % n];
  return out;
}

}  // namespace vismap::engine
