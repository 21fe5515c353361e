// Small exact helpers shared by Newell's depth sort and its overlay: split lines
// (affine functions of the screen point), which side of a line or of a facet's
// plane a polygon lies on, and bounding boxes. Internal to the engine.
#pragma once
#include <vector>

#include "engine/screen_scene.h"

namespace vismap::engine::newell {

// An exact leaf: the value computed now, so that later predicates see a number.
inline FT leaf(const FT& x) { return FT(to_mpq(x)); }

inline CGAL::Bbox_2 box_of(const std::vector<P3>& v) {
  CGAL::Bbox_2 b;
  for (const P3& p : v) {
    auto ix = CGAL::to_interval(p.x), iy = CGAL::to_interval(p.y);
    b += CGAL::Bbox_2(ix.first, iy.first, ix.second, iy.second);
  }
  return b;
}

// An affine function of the screen point, f(x, y) = a x + b y + c: a split line.
struct Line {
  FT a, b, c;
  FT at(const FT& x, const FT& y) const { return a * x + b * y + c; }
  CGAL::Sign sign_at(const P3& p) const {
    return filtered_sign([&] { return a.approx() * p.x.approx() + b.approx() * p.y.approx() + c.approx(); },
                         [&]() -> mpq_class { return to_mpq(a) * to_mpq(p.x) + to_mpq(b) * to_mpq(p.y) + to_mpq(c); });
  }
};

// Orientation of (p, q, r) on the screen: positive when r is left of p -> q.
inline CGAL::Sign orient(const P3& p, const P3& q, const P3& r) {
  return filtered_sign(
      [&] {
        return (q.x.approx() - p.x.approx()) * (r.y.approx() - p.y.approx()) -
               (q.y.approx() - p.y.approx()) * (r.x.approx() - p.x.approx());
      },
      [&]() -> mpq_class {
        return orient_sign(to_mpq(p.x), to_mpq(p.y), to_mpq(q.x), to_mpq(q.y), to_mpq(r.x), to_mpq(r.y));
      });
}

// sign((q - p) . (t - s)) and sign((q - p) x (t - s)) on the screen.
inline CGAL::Sign dot_sign(const P3& p, const P3& q, const P3& s, const P3& t) {
  return filtered_sign(
      [&] {
        return (q.x.approx() - p.x.approx()) * (t.x.approx() - s.x.approx()) +
               (q.y.approx() - p.y.approx()) * (t.y.approx() - s.y.approx());
      },
      [&]() -> mpq_class {
        return (to_mpq(q.x) - to_mpq(p.x)) * (to_mpq(t.x) - to_mpq(s.x)) +
               (to_mpq(q.y) - to_mpq(p.y)) * (to_mpq(t.y) - to_mpq(s.y));
      });
}
inline CGAL::Sign cross_sign(const P3& p, const P3& q, const P3& s, const P3& t) {
  return filtered_sign(
      [&] {
        return (q.x.approx() - p.x.approx()) * (t.y.approx() - s.y.approx()) -
               (q.y.approx() - p.y.approx()) * (t.x.approx() - s.x.approx());
      },
      [&]() -> mpq_class {
        return (to_mpq(q.x) - to_mpq(p.x)) * (to_mpq(t.y) - to_mpq(s.y)) -
               (to_mpq(q.y) - to_mpq(p.y)) * (to_mpq(t.x) - to_mpq(s.x));
      });
}

// Where the planes of facets F and G cross: f = depth_F - depth_G.
inline Line plane_crossing(const Facet& F, const Facet& G) {
  return {F.plane->number(0) - G.plane->number(0), F.plane->number(1) - G.plane->number(1),
          F.plane->number(2) - G.plane->number(2)};
}

// The line through screen points p and q (positive to the left of p -> q).
inline Line line_through(const P3& p, const P3& q) {
  FT a = p.y - q.y, b = q.x - p.x;
  return {a, b, -(a * p.x + b * p.y)};
}

// Where the line f = 0 crosses segment a -> b, f changing sign strictly between
// them: an exact leaf point (x, y).
inline std::pair<FT, FT> edge_crossing(const P3& a, const P3& b, const Line& f) {
  const FT fa = f.at(a.x, a.y), fb = f.at(b.x, b.y);
  const FT t = fa / (fa - fb);
  return {leaf(a.x + t * (b.x - a.x)), leaf(a.y + t * (b.y - a.y))};
}

// The depth of facet F's plane at (x, y).
inline FT depth_of(const Facet& F, const FT& x, const FT& y) {
  return F.plane->number(0) * x + F.plane->number(1) * y + F.plane->number(2);
}

// Which sides of a line (or plane) a polygon has vertices strictly on.
enum : int { kNeg = 1, kPos = 2, kBoth = 3 };

inline int sides_of(const std::vector<P3>& v, const Line& f) {
  int s = 0;
  for (const P3& p : v) {
    auto g = f.sign_at(p);
    s |= g > 0 ? kPos : g < 0 ? kNeg : 0;
    if (s == kBoth) break;
  }
  return s;
}

// sign(p.z - depth of G at p): positive when p is behind G's plane. Where p is
// input vertex `id` (else -1) and the intervals cannot tell, p in G's plane
// (coplanar neighbours: the zero no filter settles) is told in the `world`
// before any rational is made.
inline CGAL::Sign plane_side(const P3& p, const Facet& G, const std::vector<Vec3>* world = nullptr, long id = -1) {
  return filtered_sign(
      [&] {
        return p.z.approx() - (G.plane->approx(0) * p.x.approx() + G.plane->approx(1) * p.y.approx() + G.plane->approx(2));
      },
      [&]() -> mpq_class {
        if (world && id >= 0 && in_world_plane(*world, id, G)) return 0;
        const auto P = G.plane->exact();
        return to_mpq(p.z) - (P[0] * to_mpq(p.x) + P[1] * to_mpq(p.y) + P[2]);
      });
}

// p is one of G's own vertices (the very same numbers, as where facets of a mesh
// share a vertex): in G's plane, with no arithmetic.
inline bool is_vertex_of(const P3& p, const Facet& G) {
  for (const P3& q : G.v)
    if (p.x.identical(q.x) && p.y.identical(q.y) && p.z.identical(q.z)) return true;
  return false;
}

// Relative to the plane of facet G (index g): kPos = strictly behind (deeper),
// kNeg = strictly in front (nearer); 0: in the plane. `cut_on[k]` (may be empty)
// names a facet whose plane vertex k is known to lie on (it was cut there).
// (Points: a fragment's own points, or a facet's corners.)
template <class Points>
int sides_of_plane(const Points& v, const std::vector<int>& cut_on, int g, const Facet& G) {
  int s = 0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (!cut_on.empty() && cut_on[k] == g) continue;
    if (is_vertex_of(v[k], G)) continue;
    const auto c = plane_side(v[k], G);
    s |= c == CGAL::POSITIVE ? kPos : c == CGAL::NEGATIVE ? kNeg : 0;
    if (s == kBoth) break;
  }
  return s;
}
constexpr int kBehind = kPos, kFront = kNeg;

}  // namespace vismap::engine::newell
