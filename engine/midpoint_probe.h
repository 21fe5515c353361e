// The point where a piece of a curve is decided (its midpoint), and the
// predicates both engines ask there, as filtered signs: intervals first, exact
// rationals where those cannot tell, and no lazy number built. Internal to the
// engine (CGAL types).
#pragma once
#include <vector>

#include "engine/screen_scene.h"

namespace vismap::engine {
VISMAP_KERNEL_BEGIN

// The point m where a piece is decided, and its curve's direction, as exact
// numbers and as intervals: the comparisons below run on the intervals and fall
// back to rationals only when those cannot decide (no lazy trees are built).
struct Probe {
  const P2 *a, *b;            // the piece's ends: m is their midpoint
  Interval ix, iy;            // m
  const Curve* curve;         // end points s, t: direction t - s
  const P3 *s, *t;
  const std::vector<Vec3>* world;   // the input's vertices (the curve's end point ids index them)
  const ScreenScene* screen;        // whose facets the curve's sharers are
  const ExactSource* orthographic = nullptr;   // the scene's, in an orthographic view (else null)
  Interval idx, idy;
  bool x_moves = true;        // t.x != s.x (else the curve is vertical)
  mpq_class ex, ey, edx, edy; // exact values, filled on first need
  bool have_exact = false, have_direction = false;
  // Set where m turned out to lie on a facet's edge line across the curve
  // (cover_at): m tells nothing of either side there.
  bool on_crossing_line = false;
  void at_midpoint(const P2& pa, const P2& pb) {   // (rounding upward: the caller's UpwardRounding)
    a = &pa;
    b = &pb;
    ix = (approx_x(pa) + approx_x(pb)) / 2;
    iy = (approx_y(pa) + approx_y(pb)) / 2;
    have_exact = false;
  }
  void need_direction() {   // (the curve's: the same for every piece)
    if (have_direction) return;
    NearestRounding nearest;
    edx = to_mpq(t->x) - to_mpq(s->x);
    edy = to_mpq(t->y) - to_mpq(s->y);
    have_direction = true;
  }
  void need_exact() {
    if (have_exact) return;
    need_direction();
    NearestRounding nearest;
    ex = (exact_x(*a) + exact_x(*b)) / 2;
    ey = (exact_y(*a) + exact_y(*b)) / 2;
    have_exact = true;
  }
};

// Whether curve cv runs at least as much along x as along y on the screen
// (|dx| >= |dy|: its points are ordered by x), decided on its end points'
// numbers (no lazy coordinate or difference built).
bool mostly_along_x(const Curve& cv);

// The probe of curve cv of ss (its direction set; at_midpoint sets the point).
Probe probe_of(const ScreenScene& ss, const Curve& cv);

// Orientation of (p, q, m): positive when m is left of p -> q. ip, iq: p's and
// q's canonical vertex ids, or -1 (a near-plane cut's point).
CGAL::Sign orientation(const P3& p, const P3& q, VertexId ip, VertexId iq, Probe& m);
// The same where ip and iq are two input vertices whose images span the line
// p -> q in either direction (a Newell fragment's side on its facet's edge).
CGAL::Sign orientation_on_spanned_line(const P3& p, const P3& q, VertexId ip, VertexId iq, Probe& m);
// sign((q - p) . (t - s)): a facet edge's direction against the curve's.
CGAL::Sign edge_along(const P3& p, const P3& q, Probe& m);
// sign((q - p) x (t - s)): zero where a facet edge runs parallel to the curve.
// ip, iq: p's and q's canonical vertex ids, or -1 (a near-plane cut's point).
CGAL::Sign edge_across(const P3& p, const P3& q, VertexId ip, VertexId iq, Probe& m);
// sign(depth of f - depth of g) at m.
CGAL::Sign depth_order(const Facet& f, const Facet& g, Probe& m);
// sign(slope of f - slope of g), the slope being the rate at which depth grows
// along the curve's left normal (-dy, dx).
CGAL::Sign slope_order(const Facet& f, const Facet& g, Probe& m);
// sign(depth of f at m - depth of the curve at m), the curve's depth
// interpolated from its end points along x (or y, for a vertical curve).
CGAL::Sign depth_against_curve(const Facet& f, Probe& m);

VISMAP_KERNEL_END
}  // namespace vismap::engine
