// The scene as the checker sees it on the screen: every input polygon turned
// into pieces (the polygon itself, or its fan triangles when non-planar),
// projected through the map's own view matrix and clipped at the near plane.
#pragma once
#include <gmpxx.h>

#include <array>
#include <cstdint>
#include <vector>

#include "engine/scene.h"
#include "verify/failures.h"
#include "verify/geom.h"
#include "verify/map_doc.h"

namespace vismap_check {

// What an edge of a piece is: a polygon edge, a fan diagonal (inside the
// polygon: never drawn, never an edge piece), or a cut made by the near plane.
enum class Role : std::uint8_t { Boundary, Diagonal, Clip };

struct Piece {
  std::uint32_t face = 0;
  std::vector<P2> xy;                   // screen positions, no two consecutive equal
  std::vector<mpq_class> depth;         // depth of each vertex
  std::vector<Role> role;               // role[i]: edge xy[i] -> xy[next(i)]
  // A face with holes is one piece of several rings, one after another in xy:
  // the outer ring first, then the holes, each turned against the outer one
  // (so the piece lies on the same side of every edge). ring_next[i] is the
  // corner after i in its ring; empty for a piece of one ring.
  std::vector<std::uint32_t> ring_next;
  std::size_t next(std::size_t i) const {
    return ring_next.empty() ? (i + 1 == xy.size() ? 0 : i + 1) : ring_next[i];
  }
  int orient = 0;                       // +1 front-facing, -1 back-facing, 0 edge-on
  bool convex = false;                  // projection convex (and not edge-on)
  mpq_class pa, pb, pc;                 // depth = pa x + pb y + pc (orient != 0)
  std::array<mpq_class, 3> normal;      // world normal, right-hand rule (creases)
  Box box;

  mpq_class depth_at(const P2& q) const {
    mpq_class d = pa * q.x + pb * q.y + pc;
    return d;
  }
  // d(depth)/dt along q + t s: a plane's slope in direction s.
  mpq_class slope_along(const P2& s) const {
    mpq_class d = pa * s.x + pb * s.y;
    return d;
  }
  bool same_plane(const Piece& o) const { return pa == o.pa && pb == o.pb && pc == o.pc; }
  // Sign of depth_at(q) - d by integer arithmetic (no gcd): the hot comparison.
  int depth_cmp(const P2& q, const mpq_class& d) const;

  mpz_class ia, ib, ic, il;             // il depth = ia x + ib y + ic, il > 0 (orient != 0)
};

// Where q is against the piece's rings (even-odd over all of them).
Where locate(const P2& q, const Piece& p);

struct Screen {
  std::vector<Piece> pieces;            // in face order
  BoxGrid grid;                         // over the pieces' boxes
  std::size_t faces = 0;                // polygons in the scene
  mpq_class cos_crease;                 // the double cos(theta*pi/180), exactly
  bool smooth = false;                  // smooth edges are drawn
};

// Projects the scene with doc's matrix. Problems with the matrix itself (W <= 0
// at a kept point) go to `fail`.
Screen make_screen(const vismap::Scene& scene, const MapDoc& doc, double crease_deg, bool smooth,
                   Failures& fail);

// The kind of an edge piece shared by the given pieces, one per distinct face.
Kind edge_kind(const std::vector<const Piece*>& owners, const mpq_class& cos_crease);

// n1.n2 < c |n1| |n2|, exactly (|n| is irrational: compare squares with signs).
bool is_crease(const std::array<mpq_class, 3>& n1, const std::array<mpq_class, 3>& n2, const mpq_class& c);

}  // namespace vismap_check
