// The geometric checks of check_map, one file each; they share this context.
#pragma once
#include <functional>
#include "verify/checker.h"
#include "verify/failures.h"
#include "verify/local.h"
#include "verify/map_doc.h"
#include "verify/screen.h"

namespace vismap_check {

struct Context {
  const Screen& sc;
  const MapDoc& doc;
  const Options& opt;
  Failures& fail;
  Report& rep;
};

void check_regions(Context& c);    // 4: random samples, label against brute force
void check_area(Context& c);       // 5: total area of the regions = area of the union
void check_segments(Context& c);   // 6: each segment is a visible line of the right kind
void check_coverage(Context& c);   // 7: each visible edge / intersection line is drawn
void check_topology(Context& c);   // segments meet only at endpoints; no superfluous vertex
void check_hidden(Context& c);     // 8: the hidden lines, where the map has them

std::string describe(const std::vector<std::uint32_t>& faces, Kind k);   // "crease [3,4]"

// Segments whose closed extent holds q: of `list` (over which `grid` is built),
// or of the map's segments.
std::vector<std::size_t> segments_at(const std::vector<MapSegment>& list, const BoxGrid& grid, const P2& q);
inline std::vector<std::size_t> segments_at(const MapDoc& doc, const P2& q) {
  return segments_at(doc.segments, doc.segment_grid, q);
}

// Why no visible drawn line is at a point (for messages), from its LineView.
std::string why_nothing(const LineView& lv);

// The line under segment `seg` (direction s = to - from): the depths at its ends
// of the edge piece or intersection line with its kind and faces (with
// hidden_only: one not visible there), from two clean interior points (depth is
// affine along a screen line). False if not found.
bool depth_line(const Context& c, const MapSegment& seg, const P2& s, mpq_class& da, mpq_class& db, bool hidden_only);

// Interior sample parameters along a segment, simplest first (1/2, 1/3, 2/3, ...).
std::vector<mpq_class> parameters();

// Every crossing of two faces' pieces (not edge-on, boxes meeting): f(faces,
// p, a, b, dir) for each stretch a-b of it inside both, p the first piece.
void for_each_crossing(const Screen& sc, const std::function<void(const std::vector<std::uint32_t>& faces, const Piece& p,
                                                                   const P2& a, const P2& b, const P2& dir)>& f);

// The stretches of the line where the planes of pieces p and r meet that lie
// inside both projections, as pairs of end points; `dir` is the line's direction.
std::vector<std::pair<P2, P2>> crossing_stretches(const Piece& p, const Piece& r, P2& dir);

// Parameters 0 = t0 < t1 < ... < 1 along the screen segment a -> b (depth da -> db)
// between which nothing over the line changes (check_coverage.cpp).
std::vector<mpq_class> stretch_params(const Screen& sc, const MapDoc& doc, const P2& a, const P2& b,
                                      const mpq_class& da, const mpq_class& db);

}  // namespace vismap_check
