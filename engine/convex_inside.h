// Whether a point lies strictly inside a convex polygon, in O(log n) orientation
// tests for polygons with many corners (a cylinder's cap, a disk: a planar
// convex polygon is one facet, of up to 10^6 corners). Internal to the engines.
#pragma once
#include <cstddef>

namespace vismap::engine {

// orient(i, j): the sign (-1, 0, 1) of the point against the directed line
// v_i -> v_j (positive: to its left); turn: +1 for a counter-clockwise polygon,
// -1 for a clockwise one. A few corners: every side is asked. More: the fan from
// v_0 is searched for the wedge (v_0, v_k, v_k+1) that holds the point (the
// rays v_0 -> v_k turn monotonically, through at most a half turn, so the signs
// against them fall once), and only the sides at v_0 and side k decide: a point
// strictly left of v_0 -> v_k, on or right of v_0 -> v_k+1 and strictly left of
// v_k -> v_k+1 and of both sides at v_0 lies in the triangle (v_0, v_k, v_k+1)
// off its boundary, or on the diagonal v_0 v_k+1 (a diagonal: the sides at v_0
// exclude the ones on a side), so strictly inside.
template <class Orient>
bool strictly_inside_convex(std::size_t n, int turn, Orient&& orient) {
  if (n <= 8) {
    for (std::size_t k = 0; k < n; ++k)
      if (orient(k, (k + 1) % n) * turn <= 0) return false;
    return true;
  }
  if (orient(0, 1) * turn <= 0) return false;       // on or right of side 0
  if (orient(0, n - 1) * turn >= 0) return false;   // on or right of side n-1 (v_n-1 -> v_0)
  std::size_t lo = 1, hi = n - 1;                  // sign at lo > 0, at hi <= 0
  while (hi - lo > 1) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (orient(0, mid) * turn > 0) lo = mid;
    else hi = mid;
  }
  return orient(lo, lo + 1) * turn > 0;
}

}  // namespace vismap::engine
