// Cuts shared by collinear curves that overlap, for both engines' curve cutting
// (franklin_grid.cpp, newell_overlay.cpp). Internal to the engine (CGAL types).
#pragma once
#include <algorithm>
#include <utility>
#include <vector>

#include "engine/screen_scene.h"
#include "engine/union_find.h"

namespace vismap::engine {
VISMAP_KERNEL_BEGIN

// Collinear curves that overlap are cut at the same points, so that their pieces
// coincide where they overlap (the map is assembled from pieces that meet only at
// their end points): each gets the cuts and end points of the curves it overlaps,
// directly or through others on the same line, that lie inside it. A cut made on
// one of them alone would otherwise be missing on the others: where it pierces a
// plane, or where its depth crosses a third collinear curve's. Curves that
// coincide on the screen are different lines in depth, so such points differ
// from curve to curve.
//
// overlaps: pairs of curves sharing more than a point (sorted here, repeats
// dropped). own(c): curve c's cuts so far (const std::vector<P2>*, nullptr: none).
// add(c, first, last): appends the points [first, last) to curve c's cuts.
template <class Own, class Add>
void share_overlap_cuts(const std::vector<Curve>& curves, std::vector<std::pair<int, int>>& overlaps, Own&& own,
                        Add&& add) {
  if (overlaps.empty()) return;
  std::sort(overlaps.begin(), overlaps.end());
  overlaps.erase(std::unique(overlaps.begin(), overlaps.end()), overlaps.end());
  UnionFind lines(curves.size());
  for (const auto& [c, d] : overlaps) lines.join(c, d);
  std::vector<std::pair<int, int>> members;   // (line, curve)
  for (const auto& [c, d] : overlaps) {
    members.emplace_back(lines.find(c), c);
    members.emplace_back(lines.find(d), d);
  }
  std::sort(members.begin(), members.end());
  members.erase(std::unique(members.begin(), members.end()), members.end());
  std::vector<P2> points;
  for (std::size_t k = 0; k < members.size();) {
    std::size_t l = k;
    points.clear();
    for (; l < members.size() && members[l].first == members[k].first; ++l) {
      const Curve& C = curves[members[l].second];
      if (const std::vector<P2>* cuts = own(members[l].second)) points.insert(points.end(), cuts->begin(), cuts->end());
      points.push_back(C.s->xy());
      points.push_back(C.t->xy());
    }
    // The points in order along the common line (by x, or by y on a vertical line),
    // each once; each curve takes those strictly between its ends: O(P log P) for
    // P points, where asking every point of every curve was O(P^2) (the edges of
    // walls seen edge-on, all on one screen line: minutes on a CAD part).
    const Curve& C0 = curves[members[k].second];
    const bool use_x = CGAL::compare_x(C0.s->xy(), C0.t->xy()) != CGAL::EQUAL;
    auto less = [&](const P2& a, const P2& b) { return compare_coordinate_exactly(a, b, use_x) == CGAL::SMALLER; };
    std::sort(points.begin(), points.end(), less);
    points.erase(std::unique(points.begin(), points.end(), [&](const P2& a, const P2& b) { return !less(a, b); }),
                 points.end());
    for (std::size_t m = k; m < l; ++m) {
      const int ci = members[m].second;
      const Curve& C = curves[ci];
      const bool forward = less(C.s->xy(), C.t->xy());
      const P2 &lo = forward ? C.s->xy() : C.t->xy(), &hi = forward ? C.t->xy() : C.s->xy();
      const auto first = std::upper_bound(points.begin(), points.end(), lo, less);
      const auto last = std::lower_bound(first, points.end(), hi, less);
      if (first != last) add(ci, first, last);
    }
    k = l;
  }
}

VISMAP_KERNEL_END
}  // namespace vismap::engine
