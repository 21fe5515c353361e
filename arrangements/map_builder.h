// Visible and boundary pieces -> the canonical visibility map (regions, segments).
// Internal to the core: takes exact kernel types.
#pragma once
#include <vector>

#include "arrangements/visibility_map.h"
#include "engine/exact_kernel.h"

namespace vismap {
VISMAP_KERNEL_BEGIN

struct MapPiece {
  exact::P2 a, b;                    // a != b
  exact::FT za, zb;                  // depth at a and b (for coincident lines)
  int left = -1, right = -1;         // nearest face left / right of a -> b (-1: none)
  bool drawn = false;                // a visible line
  EdgeKind kind = EdgeKind::Border;
  const std::vector<int>* faces = nullptr;
  int order_face = 0;                // lowest face index, for ties in depth
};

// Builds the planar arrangement of the pieces (CGAL Arrangement_2, overlaps
// merged), labels its faces, drops superfluous vertices and writes the regions
// and segments in canonical order into `map`. Throws std::logic_error if the
// labels are inconsistent (a bug, never bad input).
void build_map(std::vector<MapPiece>& pieces, VisibilityMap& map);

VISMAP_KERNEL_END

// A piece computed in doubles by the float variant of the engine (benchmarks
// only), handed to the exact arrangement builder. Pieces whose ends coincide
// are dropped.
struct FloatPiece {
  double ax, ay, bx, by, za, zb;
  int left = -1, right = -1;
  bool drawn = false;
  EdgeKind kind = EdgeKind::Border;
  const std::vector<int>* faces = nullptr;
  int order_face = 0;
};
void build_map_from_floats(std::vector<FloatPiece>& pieces, VisibilityMap& map);   // in the exact build

}  // namespace vismap
