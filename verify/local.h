// What the spec says is at one screen point: the visible face there (regions),
// or the edge pieces and intersection lines running through it along a given
// screen direction, with their order keys and visibility (segments).
#pragma once
#include <gmpxx.h>

#include <cstdint>
#include <vector>

#include "verify/geom.h"
#include "verify/map_doc.h"
#include "verify/screen.h"

namespace vismap_check {

// Label at a point for the region check. clean == false when q lies on a
// projected edge of any piece, or two different faces tie for nearest with
// different planes (q on an intersection line): no single label is defined.
struct PointLabel {
  bool clean = false;
  long face = -1;   // -1: background
};
PointLabel label_at(const Screen& sc, const P2& q);

// A line through q along the direction s, as the spec defines them.
struct LineItem {
  Kind kind = Kind::Border;
  std::vector<std::uint32_t> faces;   // ascending
  mpq_class depth;                    // depth of the 3D point over q
  bool visible = false;
  bool drawn = false;
  bool cut = false;   // a near-plane cut: no edge of its face, so a line only where no edge is
  // Order (depth, lowest face index); where the spec leaves a tie (two lines of
  // one face, e.g. intersection lines with faces 1,7 and 1,8 along one 3D line),
  // the faces lists lexicographically.
  bool before(const LineItem& o) const {
    return depth < o.depth || (depth == o.depth && faces < o.faces);
  }
  bool same_key(const LineItem& o) const { return depth == o.depth && faces == o.faces; }
};

struct LineView {
  // clean == false: q is a vertex of the situation (a projected vertex, a
  // crossing edge, an edge piercing a face, crossing lines in 3D...), where the
  // answer may differ from both sides; such points are skipped.
  bool clean = false;
  std::vector<LineItem> items;
  // The visible items first in the order (several only on exact ties), drawn or
  // not; near-plane cuts only where no edge piece or intersection line is visible.
  std::vector<const LineItem*> first_visible() const;
  // What the map draws there: first_visible(), or nothing where that is not drawn
  // (a smooth seam in front covers the lines behind it, drawn or not).
  std::vector<const LineItem*> first() const;
};

// s != 0 is the screen direction of the line through q.
LineView look_along(const Screen& sc, const P2& q, const P2& s);

}  // namespace vismap_check
