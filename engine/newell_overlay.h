// Newell's ordered fragments -> the pieces of the visibility map. Every line that
// may be drawn or bound a region (edges, near-plane cuts, and the intersection
// lines of faces that pierce each other) is cut wherever anything on it can
// change, and each piece is classified at its midpoint by the drawing order:
// what is painted just beside it, and whether a later fragment paints over it.
// Internal to the engine.
#pragma once
#include <vector>

#include "arrangements/map_builder.h"
#include "engine/engine_run.h"
#include "engine/newell_order.h"
#include "engine/visibility.h"

namespace vismap::engine {

// Faces that pierce each other: appends to ss.curves, for every two occluding
// facets of different faces whose planes cross inside both projections, the
// segment where they cross (the overlap of the two chords the crossing line
// cuts from them).
void add_piercing_lines(ScreenScene& ss, Stats& stats);

// Drops the curves that one fragment covers whole and lies strictly in front of
// (both ends strictly inside its projection, strictly behind its plane): they
// are hidden, and bound nothing (the same fragment's face is on both sides).
// Only fragments of planar polygons drop curves (see the .cpp).
void drop_painted_over(ScreenScene& ss, const std::vector<Fragment>& order, Stats& stats);

// Where each curve must be cut: every point where another curve crosses it or
// ends on it, the ends of a collinear overlap, where two collinear curves'
// depths cross, and where a line of edge-on faces only pierces an occluding
// facet (no intersection line ends there); and each of these on every curve
// that overlaps the cut one on its screen line (share_overlap_cuts), so that the
// pieces of any two curves meet only at their end points. Unsorted, possibly
// repeated. With them, which curves are upright on the screen (their ends' x
// exactly equal), and for cut points whose x is known as a number with a cheap
// exact value (MapPiece::xa: a crossing with an upright curve, that line's x;
// another curve's end point, its own), that number, by the point's
// representation.
struct CutPoints {
  std::vector<std::vector<P2>> at;   // per curve
  std::vector<char> upright;         // per curve
  std::vector<std::pair<CGAL::Handle::Id_type, const FT*>> known_x;   // sorted
  const FT* x_of(const P2& p) const;   // (null: not known)
};
CutPoints cut_at_crossings(const ScreenScene& ss, Stats& stats);

// Each piece between consecutive cuts, judged at its midpoint m from `order`
// (drawing order): the face on each side is the last-drawn fragment covering the
// points just beside m; a drawn curve is hidden where a fragment of a face not
// its own covers both sides of m and is painted over it (drawn after its own
// fragment; at exactly equal depth, the spec's face-index rule). Keeps the
// visible pieces and those with different faces on their two sides, one piece
// per pair of consecutive cuts (never joined: assemble_map wants pieces that meet
// only at their end points, and a joined piece would pass over a cut that
// another curve's piece ends at). The pieces point at their curve's list in
// `faces` (faces_lists).
std::vector<MapPiece> paint_pieces(const ScreenScene& ss, const std::vector<Fragment>& order, CutPoints& cuts,
                                   const std::vector<FacesList>& faces, Stats& stats);

// Everything after the drawing order, for Newell's engine and the BSP engine
// (bsp.cpp): the pieces above, the map, its stats and hidden lines, and the
// painter's fragments when asked. `filter_before`: the filter counts at the start.
void map_from_order(const Scene& scene, const View& view, const Options& opt, ScreenScene& ss,
                    const std::vector<Fragment>& order, VisibilityMap& map, PhaseClock& clock,
                    const exact::FilterCounts& filter_before, std::vector<PaintedFragment>* painter);

}  // namespace vismap::engine
