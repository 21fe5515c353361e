// Visible and boundary pieces -> the canonical visibility map (regions, segments).
// Internal to the core: takes exact kernel types.
#pragma once
#include <vector>

#include "arrangements/visibility_map.h"
#include "engine/exact_kernel.h"
#include "engine/small_vec.h"

namespace vismap {

// A written segment's faces, ascending (inline: one or two almost always).
using FacesList = engine::SmallInts;

VISMAP_KERNEL_BEGIN

struct MapPiece {
  exact::P2 a, b;                    // a != b
  const exact::P3 *s = nullptr, *t = nullptr;   // its line with depths (two points of it),
                                     // which ranks coincident lines
  int left = -1, right = -1;         // nearest face left / right of a -> b (-1: none)
  bool visible = false;              // a visible edge piece or intersection line: it competes
                                     // with the lines coinciding with it, drawn or not
  bool drawn = false;                // visible, and of a kind that is drawn
  EdgeKind kind = EdgeKind::Border;
  const FacesList* faces = nullptr;
  int order_face = 0;                // lowest face index, for ties in depth
  int line = -1;                     // the engine's curve it lies on (-1: not known): pieces
                                     // of one curve are collinear, known without arithmetic
  // A number equal to a's (b's) x whose exact value is cheap, where the engine
  // knows one: a vertex image's x, or on an upright screen line (a vertical edge
  // seen with the up axis upright: common) that line's. The end points' x then
  // compare without the points' own exact values (crossings, mostly: the
  // costliest numbers). Null: not known.
  const exact::FT *xa = nullptr, *xb = nullptr;
  // A name for a's (b's) point where the engine has one: pieces whose ends have
  // one id end at one point (a mesh vertex's canonical id: on a mesh most ends
  // are its vertices, each shared by about six pieces). -1: none.
  int ida = -1, idb = -1;
};

// Builds the planar arrangement of the pieces (CGAL Arrangement_2, overlaps
// merged), labels its faces, drops superfluous vertices and writes the regions
// and segments in canonical order into `map`. Throws std::logic_error if the
// labels are inconsistent (a bug, never bad input).
void build_map(std::vector<MapPiece>& pieces, VisibilityMap& map);

// The same map from pieces that meet only at their end points (no piece crosses
// or partly overlaps another; pieces on the same two end points are merged),
// without a sweep: Franklin's pieces, which step 8 cut at every crossing. Throws
// std::logic_error where the pieces break that promise in a way it detects.
// Its sorts run on `threads` threads; the map is the same for every count.
// (engine/franklin.cpp calls its two halves, graph_of_pieces and finish_map in
// map_graph.h, to free its curves in between.)
void assemble_map(std::vector<MapPiece>& pieces, VisibilityMap& map, int threads = 1);

// The segments of that map alone (map.has_regions false), from the drawn pieces
// and the pieces of every curve that meets a drawn one (visible or bounding a
// region), cut as assemble_map wants them; other pieces are not needed.
void assemble_segments(std::vector<MapPiece>& pieces, VisibilityMap& map, int threads = 1);

VISMAP_KERNEL_END

// A piece computed in doubles by the float variant of the engine (benchmarks
// only), handed to the assembly (assemble_map) with its doubles taken as exact.
// Pieces whose ends coincide are dropped.
struct FloatPiece {
  double ax, ay, bx, by, za, zb;
  int left = -1, right = -1;
  bool visible = false, drawn = false;
  EdgeKind kind = EdgeKind::Border;
  const FacesList* faces = nullptr;
  int order_face = 0;
};
void build_map_from_floats(std::vector<FloatPiece>& pieces, VisibilityMap& map);   // in the exact build

}  // namespace vismap
