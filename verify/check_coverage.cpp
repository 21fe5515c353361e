// Check 7: every visible, drawn edge piece and intersection line appears in
// the map. Each polygon edge and each crossing of two faces is cut where
// anything over it may change, and every stretch is tested at its midpoint:
// no visible piece, however short, goes unchecked.
#include <algorithm>
#include <functional>

#include "verify/checks.h"
#include "verify/local.h"
#include "verify/rational.h"

namespace vismap_check {

// Parameters t in (0, 1), with 0 and 1, along the screen segment a -> b
// (depth da -> db) where what lies over it may change: crossings with projected
// edges, ends of collinear edges, and depth crossings with collinear edges and
// with face planes. Between two consecutive ones, which faces cover the line,
// whether they are in front, and the order of coincident lines are constant,
// so the midpoints of these stretches test the whole segment. The map's own
// vertices on the segment are added too: intersection lines crossing it may
// split its segments where none of the above happens, and every piece between
// two map vertices must be looked at.
std::vector<mpq_class> stretch_params(const Screen& sc, const MapDoc& doc, const P2& a, const P2& b,
                                      const mpq_class& da, const mpq_class& db) {
  const P2 s{b.x - a.x, b.y - a.y};
  const mpq_class ss = s.x * s.x + s.y * s.y;
  const mpq_class dd = db - da;
  const Box box = box_of(a, b);
  std::vector<mpq_class> ts{0, 1};
  auto add = [&](mpq_class t) {
    if (t > 0 && t < 1) ts.push_back(std::move(t));
  };
  auto param = [&](const P2& p) {
    mpq_class t = ((p.x - a.x) * s.x + (p.y - a.y) * s.y) / ss;
    return t;
  };
  for (const P2* v : vertices_on(doc, a, b)) add(param(*v));
  for (const Piece& p : sc.pieces) {
    if (!p.box.meets(box)) continue;
    if (p.orient != 0 && p.depth_cmp(a, da) * p.depth_cmp(b, db) < 0) {   // the segment pierces p's plane
      mpq_class pa = p.depth_at(a), pb = p.depth_at(b);
      add((pa - da) / (dd - (pb - pa)));
    }
    for (std::size_t i = 0, n = p.xy.size(); i < n; ++i) {
      const P2& u = p.xy[i];
      const P2& v = p.xy[p.next(i)];
      int o1 = orient(a, b, u), o2 = orient(a, b, v);
      if (o1 == 0 && o2 == 0) {   // collinear: its ends, and where it passes in depth
        const mpq_class& du = p.depth[i];
        const mpq_class& dv = p.depth[p.next(i)];
        mpq_class tu = param(u), tv = param(v);
        if (tu != tv) {
          mpq_class k = (dv - du) / (tv - tu);   // its depth per unit of t
          mpq_class den = dd - k;
          if (den != 0) add((du - k * tu - da) / den);
        }
        add(std::move(tu));
        add(std::move(tv));
        continue;
      }
      if (o1 * o2 > 0) continue;
      if (orient(u, v, a) * orient(u, v, b) > 0) continue;
      mpq_class ca = cross(u, v, a), cb = cross(u, v, b);   // not both 0: not collinear
      add(ca / (ca - cb));
    }
  }
  std::sort(ts.begin(), ts.end());
  ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
  return ts;
}

namespace {

// Where the first visible line at q (never a map vertex) is drawn, q must be
// inside a segment, and that segment must carry its kind and faces. (Where it is
// not drawn, a nearer smooth seam, no segment may lie there: check_segments.)
void require_drawn(Context& c, const P2& q, const LineView& lv, const std::string& what) {
  ++c.rep.edge_points_checked;
  auto first = lv.first();
  if (first.empty()) return;
  std::vector<std::size_t> at = segments_at(c.doc, q);
  if (at.empty()) {
    c.fail.add("coverage: no segment at " + str(q) + " where " + what + " is visible");
    return;
  }
  if (at.size() > 1) return;   // overlapping segments: reported by the topology check
  const MapSegment& seg = c.doc.segments[at[0]];
  bool match = false;
  for (const LineItem* it : first) match = match || (it->kind == seg.kind && it->faces == seg.faces);
  if (!match)
    c.fail.add("coverage: segments[" + std::to_string(at[0]) + "] " + describe(seg) + " at " + str(q) +
               ": the first visible line there is " + describe(first[0]->faces, first[0]->kind));
}

// True when one convex face (not one of `own`) lies strictly in front of the
// whole open segment a -> b and holds it inside: nothing there can be visible.
// A shortcut only: it saves cutting lines that are hidden anyway.
bool buried(const Screen& sc, const P2& a, const P2& b, const mpq_class& da, const mpq_class& db,
            const std::vector<std::uint32_t>& own) {
  const P2 m{(a.x + b.x) / 2, (a.y + b.y) / 2};
  for (std::uint32_t hi : sc.grid.near(m)) {
    const Piece& h = sc.pieces[hi];
    if (!h.convex || !h.box.contains(m) || std::find(own.begin(), own.end(), h.face) != own.end()) continue;
    int sa = h.depth_cmp(a, da), sb = h.depth_cmp(b, db);
    if (sa > 0 || sb > 0 || (sa == 0 && sb == 0)) continue;
    // Convex: both ends in the closed face and the midpoint inside put the
    // whole open segment inside.
    if (locate(m, h) == Where::Inside && locate(a, h) != Where::Outside && locate(b, h) != Where::Outside)
      return true;
  }
  return false;
}

// True when some face (not one of `own`) holds q inside and is strictly in
// front of depth d there: then nothing at that depth is visible at q. A cheap
// shortcut before the full look_along, for the many hidden stretches.
bool hidden_at(const Screen& sc, const P2& q, const mpq_class& d, const std::vector<std::uint32_t>& own) {
  for (std::uint32_t hi : sc.grid.near(q)) {
    const Piece& h = sc.pieces[hi];
    if (h.orient == 0 || !h.box.contains(q) || std::find(own.begin(), own.end(), h.face) != own.end()) continue;
    if (h.depth_cmp(q, d) < 0 && locate(q, h) == Where::Inside) return true;
  }
  return false;
}

// Strict mode, at a clean point q on a line (never a map vertex): the map has a
// segment there exactly when the spec's first visible line there is drawn, and
// then with its kind and faces; where that line is not drawn (a smooth seam) or
// nothing is visible, no segment. The winner is recomputed from look_along's
// items alone, whatever line q was reached from.
void require_winner(Context& c, const P2& q, const LineView& lv) {
  ++c.rep.edge_points_checked;
  const auto first = lv.first();
  const std::vector<std::size_t> at = segments_at(c.doc, q);
  if (first.empty()) {
    if (!at.empty())
      c.fail.add("strict: segments[" + std::to_string(at[0]) + "] " + describe(c.doc.segments[at[0]]) + " at " +
                 str(q) + ": " + why_nothing(lv));
    return;
  }
  if (at.empty()) {
    if (first[0]->cut) return;   // a near-plane cut may be drawn as its face's border, or not
    c.fail.add("strict: no segment at " + str(q) + " where " + describe(first[0]->faces, first[0]->kind) +
               " is the first visible line");
    return;
  }
  for (std::size_t i : at) {
    const MapSegment& seg = c.doc.segments[i];
    bool match = false;
    for (const LineItem* it : first) match = match || (it->kind == seg.kind && it->faces == seg.faces);
    if (!match)
      c.fail.add("strict: segments[" + std::to_string(i) + "] " + describe(seg) + " at " + str(q) +
                 ": the first visible line there is " + describe(first[0]->faces, first[0]->kind));
  }
}

// Calls f(q, depth) at the midpoint of every stretch of a -> b that is not
// plainly hidden (in strict mode, of every stretch: no shortcut).
template <class F>
void for_each_stretch(const Context& c, const P2& a, const P2& b, const mpq_class& da, const mpq_class& db,
                      const std::vector<std::uint32_t>& own, F&& f) {
  const Screen& sc = c.sc;
  const bool strict = c.opt.strict;
  if (!strict && buried(sc, a, b, da, db, own)) return;
  std::vector<mpq_class> ts = stretch_params(sc, c.doc, a, b, da, db);
  for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
    mpq_class t = (ts[k] + ts[k + 1]) / 2;
    P2 q{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
    mpq_class d = da + t * (db - da);
    if (strict || !hidden_at(sc, q, d, own)) f(q, d);
  }
}

void edges(Context& c) {
  for (const Piece& p : c.sc.pieces) {
    const std::size_t n = p.xy.size();
    for (std::size_t i = 0; i < n; ++i) {
      // Near-plane cuts are not required: the spec does not say they are lines.
      if (p.role[i] != Role::Boundary) continue;
      const P2& a = p.xy[i];
      const P2& b = p.xy[p.next(i)];
      if (a == b) continue;   // seen end-on: a point, not a line
      const P2 s{b.x - a.x, b.y - a.y};
      for_each_stretch(c, a, b, p.depth[i], p.depth[p.next(i)], {p.face}, [&](const P2& q, const mpq_class& d) {
        LineView lv = look_along(c.sc, q, s);
        if (!lv.clean) return;
        if (c.opt.strict) return require_winner(c, q, lv);
        const LineItem* mine = nullptr;
        for (const LineItem& it : lv.items)
          if (it.kind != Kind::Intersection && !it.cut && it.depth == d) mine = &it;
        if (!mine || !mine->visible || !mine->drawn) return;
        require_drawn(c, q, lv,
                      "the edge of face " + std::to_string(p.face) + " from " + str(a) + " to " + str(b) + " (" +
                          describe(mine->faces, mine->kind) + ")");
      });
    }
  }
}

}  // namespace

std::vector<std::pair<P2, P2>> crossing_stretches(const Piece& p, const Piece& r, P2& dir) {
  std::vector<std::pair<P2, P2>> out;
  mpq_class A = p.pa - r.pa, B = p.pb - r.pb, C = p.pc - r.pc;   // A x + B y + C = 0
  if (A == 0 && B == 0) return out;
  dir = P2{-B, A};
  const mpq_class dd = A * A + B * B;
  const P2 p0 = A != 0 ? P2{-C / A, 0} : P2{0, -C / B};
  auto param = [&](const P2& q) {
    mpq_class t = q.x * dir.x + q.y * dir.y;
    return t;
  };
  const mpq_class t0 = param(p0);
  auto at = [&](const mpq_class& t) {
    mpq_class h = (t - t0) / dd;
    return P2{p0.x + dir.x * h, p0.y + dir.y * h};
  };
  std::vector<mpq_class> ts;
  for (const Piece* pc : {&p, &r}) {
    for (std::size_t i = 0, n = pc->xy.size(); i < n; ++i) {
      const P2& u = pc->xy[i];
      const P2& v = pc->xy[pc->next(i)];
      mpq_class fu = A * u.x + B * u.y + C, fv = A * v.x + B * v.y + C;
      if (fu == 0) ts.push_back(param(u));
      if (fv == 0) ts.push_back(param(v));
      if (sgn(fu) * sgn(fv) < 0) {
        mpq_class k = fu / (fu - fv);
        ts.push_back(param(P2{u.x + k * (v.x - u.x), u.y + k * (v.y - u.y)}));
      }
    }
  }
  std::sort(ts.begin(), ts.end());
  ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
  for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
    P2 mid = at((ts[k] + ts[k + 1]) / 2);
    if (locate(mid, p) == Where::Inside && locate(mid, r) == Where::Inside) out.emplace_back(at(ts[k]), at(ts[k + 1]));
  }
  return out;
}

void for_each_crossing(const Screen& sc, const std::function<void(const std::vector<std::uint32_t>&, const Piece&,
                                                                   const P2&, const P2&, const P2&)>& f) {
  const auto& ps = sc.pieces;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps[i].orient == 0) continue;
    for (std::size_t j = i + 1; j < ps.size(); ++j) {
      const Piece& p = ps[i];
      const Piece& r = ps[j];
      if (r.orient == 0 || r.face == p.face || !p.box.meets(r.box)) continue;
      const std::vector<std::uint32_t> faces{std::min(p.face, r.face), std::max(p.face, r.face)};
      P2 dir;
      for (const auto& [a, b] : crossing_stretches(p, r, dir)) f(faces, p, a, b, dir);
    }
  }
}

namespace {

void intersections(Context& c) {
  for_each_crossing(c.sc, [&](const std::vector<std::uint32_t>& faces, const Piece& p, const P2& a, const P2& b,
                              const P2& dir) {
    for_each_stretch(c, a, b, p.depth_at(a), p.depth_at(b), faces, [&](const P2& q, const mpq_class&) {
      LineView lv = look_along(c.sc, q, dir);
      if (!lv.clean) return;
      if (c.opt.strict) return require_winner(c, q, lv);
      const LineItem* mine = nullptr;
      for (const LineItem& it : lv.items)
        if (it.kind == Kind::Intersection && it.faces == faces) mine = &it;
      if (!mine || !mine->visible || !mine->drawn) return;
      require_drawn(c, q, lv, "the intersection of faces " + std::to_string(faces[0]) + " and " +
                                  std::to_string(faces[1]));
    });
  });
}

}  // namespace

void check_coverage(Context& c) {
  edges(c);
  intersections(c);
}

}  // namespace vismap_check
