#include "engine/midpoint_probe.h"

#include "engine/franklin_grid.h"
#include "engine/lazy_leaves.h"

#include <optional>

namespace vismap::engine {
VISMAP_KERNEL_BEGIN

namespace {

// The signs that the curve's own geometry gives, before m's exact value (a
// midpoint of crossings: the costliest number here) is built. On scenes of
// aligned parts (walls of rooms, boxes side by side) curves run along other
// facets' edges and in other facets' planes everywhere, and seen along a
// diagonal, within rounding of them. Each is told on the curve's end points
// (input vertices mostly, whose exact values are kept), and not counted among
// the predicates: the count stays that of the questions asked.
template <class Test>
auto uncounted(Test&& test) {
  const exact::FilterCounts before = exact::filter_counts;
  NearestRounding nearest;
  const auto answer = test();
  exact::filter_counts = before;
  return answer;
}

// A sign at m that follows from the signs at the curve's ends s and t: m lies
// strictly between them on the curve, and the quantity is affine along it, so
// m has their sign where they agree or one is 0 (both 0: the whole curve
// gives 0). None where they differ: the curve crosses over, and m's sign
// depends on where.
std::optional<int> sign_between(int at_s, int at_t) {
  if (at_s * at_t < 0) return std::nullopt;
  return at_s + at_t > 0 ? 1 : at_s + at_t < 0 ? -1 : 0;
}

// What the input vertices given with a line p -> q are: p's and q's own, or
// two that span its line in either direction, which tell only whether the
// curve lies on it.
enum class LineIds { Ends, Span };

// orientation(p, q, m) from the curve's ends, before m's exact value (a
// midpoint of crossings: the costliest number here) is built. Where all four
// are input vertices seen orthographically, the world decides (ExactSource::
// screen_cross_sign: the images' rationals, a crossing's or a midpoint's
// lines mostly, never made): the edges of a lattice of boxes seen along its
// rows lie on each other's screen lines by the thousand, and seen along its
// diagonal, near them (the view's rows are rounded) by the hundred thousand.
template <LineIds ids>
std::optional<int> side_from_ends(const P3& p, const P3& q, VertexId ip, VertexId iq, const Probe& m) {
  const VertexId is = m.curve->vs, it = m.curve->vt;
  if (m.orthographic && ip >= 0 && iq >= 0 && is >= 0 && it >= 0) {
    const auto a = static_cast<std::uint32_t>(ip), b = static_cast<std::uint32_t>(iq);
    const int at_s = m.orthographic->screen_cross_sign(a, b, a, static_cast<std::uint32_t>(is));
    if constexpr (ids == LineIds::Span)
      if (at_s != 0) return std::nullopt;
    const int at_t = m.orthographic->screen_cross_sign(a, b, a, static_cast<std::uint32_t>(it));
    if constexpr (ids == LineIds::Span)
      if (at_t != 0) return std::nullopt;
    return sign_between(at_s, at_t);
  }
  return uncounted([&] {
    return sign_between(CGAL::orientation(p.xy(), q.xy(), m.s->xy()), CGAL::orientation(p.xy(), q.xy(), m.t->xy()));
  });
}

// Facet f is one of those whose edge the curve is (so the curve is in its plane).
bool holds_curve(const Facet& f, const Probe& m) {
  for (int s : m.curve->sharers)
    if (s >= 0 && m.screen->made_facet(static_cast<std::size_t>(s)) == &f) return true;
  return false;
}

// The sign of f's depth minus the curve's at m from the curve's ends (depth_above
// is the curve's minus f's), before m's exact value is built: 0 where the curve
// lies in f's plane (the edges of aligned parts lie in other facets' planes
// everywhere).
std::optional<int> depth_from_ends(const Facet& f, const Probe& m) {
  const std::optional<int> above = uncounted([&] {
    return sign_between(depth_above(*m.s, f, m.world, m.curve->vs), depth_above(*m.t, f, m.world, m.curve->vt));
  });
  if (!above) return std::nullopt;
  return -*above;
}

// Whether the curve's ends have one screen x: where both are input vertices,
// from the world (ExactSource::screen_coordinates_equal: no rational made).
bool same_x(const ScreenScene& ss, const Curve& cv) {
  if (ss.exact && cv.vs >= 0 && cv.vt >= 0)
    return ss.exact->screen_coordinates_equal(static_cast<std::uint32_t>(cv.vs), static_cast<std::uint32_t>(cv.vt), 0);
  return CGAL::compare_x(cv.s->xy(), cv.t->xy()) == CGAL::EQUAL;
}

}  // namespace

bool mostly_along_x(const Curve& cv) {
  return filtered_sign(
             [&] {
               return CGAL::abs(approx_of(cv.t->x) - approx_of(cv.s->x)) -
                      CGAL::abs(approx_of(cv.t->y) - approx_of(cv.s->y));
             },
             [&]() -> mpq_class {
               return abs(mpq_class(to_mpq(cv.t->x) - to_mpq(cv.s->x))) -
                      abs(mpq_class(to_mpq(cv.t->y) - to_mpq(cv.s->y)));
             }) != CGAL::NEGATIVE;
}

Probe probe_of(const ScreenScene& ss, const Curve& cv) {
  Probe probe;
  probe.curve = &cv;
  probe.s = cv.s;
  probe.t = cv.t;
  probe.world = ss.world;
  probe.screen = &ss;
  probe.orthographic = ss.exact && !ss.exact->perspective ? ss.exact.get() : nullptr;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    probe.idx = approx_of(cv.t->x) - approx_of(cv.s->x);
    probe.idy = approx_of(cv.t->y) - approx_of(cv.s->y);
  }
  probe.x_moves = probe.idx.inf() > 0 || probe.idx.sup() < 0 || !same_x(ss, cv);
  return probe;
}

namespace {

template <LineIds ids>
CGAL::Sign oriented(const P3& p, const P3& q, VertexId ip, VertexId iq, Probe& m) {
  return filtered_sign(
      [&] {
        return (approx_of(q.x) - approx_of(p.x)) * (m.iy - approx_of(p.y)) -
               (approx_of(q.y) - approx_of(p.y)) * (m.ix - approx_of(p.x));
      },
      [&]() -> mpq_class {
        if (const std::optional<int> side = side_from_ends<ids>(p, q, ip, iq, m)) return *side;
        m.need_exact();
        return orient_sign(to_mpq(p.x), to_mpq(p.y), to_mpq(q.x), to_mpq(q.y), m.ex, m.ey);
      });
}

}  // namespace

CGAL::Sign orientation(const P3& p, const P3& q, VertexId ip, VertexId iq, Probe& m) {
  return oriented<LineIds::Ends>(p, q, ip, iq, m);
}

CGAL::Sign orientation_on_spanned_line(const P3& p, const P3& q, VertexId ip, VertexId iq, Probe& m) {
  return oriented<LineIds::Span>(p, q, ip, iq, m);
}

CGAL::Sign edge_along(const P3& p, const P3& q, Probe& m) {
  return filtered_sign(
      [&] { return (approx_of(q.x) - approx_of(p.x)) * m.idx + (approx_of(q.y) - approx_of(p.y)) * m.idy; },
      [&]() -> mpq_class {
        m.need_direction();
        return (to_mpq(q.x) - to_mpq(p.x)) * m.edx + (to_mpq(q.y) - to_mpq(p.y)) * m.edy;
      });
}

CGAL::Sign edge_across(const P3& p, const P3& q, VertexId ip, VertexId iq, Probe& m) {
  return filtered_sign(
      [&] { return (approx_of(q.x) - approx_of(p.x)) * m.idy - (approx_of(q.y) - approx_of(p.y)) * m.idx; },
      [&]() -> mpq_class {
        // Input vertices seen orthographically: the world decides, without the
        // images' rationals (aligned parts' parallel edges: most that come here).
        const VertexId is = m.curve->vs, it = m.curve->vt;
        if (m.orthographic && ip >= 0 && iq >= 0 && is >= 0 && it >= 0)
          return m.orthographic->screen_cross_sign(static_cast<std::uint32_t>(ip), static_cast<std::uint32_t>(iq),
                                                   static_cast<std::uint32_t>(is), static_cast<std::uint32_t>(it));
        m.need_direction();
        return (to_mpq(q.x) - to_mpq(p.x)) * m.edy - (to_mpq(q.y) - to_mpq(p.y)) * m.edx;
      });
}

CGAL::Sign depth_order(const Facet& f, const Facet& g, Probe& m) {
  return filtered_sign(
      [&] {
        return (f.plane->approx(0) - g.plane->approx(0)) * m.ix + (f.plane->approx(1) - g.plane->approx(1)) * m.iy +
               (f.plane->approx(2) - g.plane->approx(2));
      },
      [&]() -> mpq_class {
        if (holds_curve(f, m) && holds_curve(g, m)) return 0;   // (both hold m, on their common edge)
        if (uncounted([&] { return *f.plane == *g.plane; })) return 0;
        m.need_exact();
        const auto F = f.plane->exact(), G = g.plane->exact();
        return (F[0] - G[0]) * m.ex + (F[1] - G[1]) * m.ey + (F[2] - G[2]);
      });
}

CGAL::Sign slope_order(const Facet& f, const Facet& g, Probe& m) {
  return filtered_sign(
      [&] { return (f.plane->approx(1) - g.plane->approx(1)) * m.idx - (f.plane->approx(0) - g.plane->approx(0)) * m.idy; },
      [&]() -> mpq_class {
        m.need_direction();
        const auto F = f.plane->exact(), G = g.plane->exact();
        return (F[1] - G[1]) * m.edx - (F[0] - G[0]) * m.edy;
      });
}

CGAL::Sign depth_against_curve(const Facet& f, Probe& m) {
  return filtered_sign(
      [&] {
        const Interval lambda = m.x_moves ? (m.ix - approx_of(m.s->x)) / m.idx : (m.iy - approx_of(m.s->y)) / m.idy;
        const Interval z = approx_of(m.s->z) + lambda * (approx_of(m.t->z) - approx_of(m.s->z));
        return f.plane->approx(0) * m.ix + f.plane->approx(1) * m.iy + f.plane->approx(2) - z;
      },
      [&]() -> mpq_class {
        if (const std::optional<int> depth = depth_from_ends(f, m)) return *depth;
        m.need_exact();
        const mpq_class lambda = m.x_moves ? mpq_class((m.ex - to_mpq(m.s->x)) / m.edx)
                                           : mpq_class((m.ey - to_mpq(m.s->y)) / m.edy);
        const mpq_class z = to_mpq(m.s->z) + lambda * (to_mpq(m.t->z) - to_mpq(m.s->z));
        const auto F = f.plane->exact();
        return F[0] * m.ex + F[1] * m.ey + F[2] - z;
      });
}

VISMAP_KERNEL_END
}  // namespace vismap::engine
