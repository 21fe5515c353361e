// Check 7: every visible, drawn edge piece and intersection line appears in
// the map, tested at a few interior points of every polygon edge and of every
// crossing of two faces.
#include <algorithm>

#include "tests/checker/checks.h"
#include "tests/checker/local.h"
#include "tests/checker/rational.h"

namespace vismap_check {
namespace {

// q must be covered by a segment; when q is inside exactly one segment, that
// segment must carry the kind and faces of the first visible line there.
void require_drawn(Context& c, const P2& q, const LineView& lv, const std::string& what) {
  ++c.rep.edge_points_checked;
  std::vector<std::size_t> at = segments_at(c.doc, q);
  if (at.empty()) {
    c.fail.add("coverage: no segment at " + str(q) + " where " + what + " is visible");
    return;
  }
  if (at.size() != 1) return;
  const MapSegment& seg = c.doc.segments[at[0]];
  if (q == seg.from || q == seg.to) return;
  auto first = lv.first();
  bool match = false;
  for (const LineItem* it : first) match = match || (it->kind == seg.kind && it->faces == seg.faces);
  if (!match && !first.empty())
    c.fail.add("coverage: segments[" + std::to_string(at[0]) + "] " + describe(seg) + " at " + str(q) +
               ": the first visible line there is " + describe(first[0]->faces, first[0]->kind));
}

void edges(Context& c) {
  static const mpq_class ts[] = {mpq_class(1, 7), mpq_class(3, 7), mpq_class(5, 7), mpq_class(1, 2)};
  for (const Piece& p : c.sc.pieces) {
    const std::size_t n = p.xy.size();
    for (std::size_t i = 0; i < n; ++i) {
      // Near-plane cuts are not required: the spec does not say they are lines.
      if (p.role[i] != Role::Boundary) continue;
      const P2& a = p.xy[i];
      const P2& b = p.xy[(i + 1) % n];
      if (a == b) continue;   // seen end-on: a point, not a line
      const mpq_class& da = p.depth[i];
      const mpq_class& db = p.depth[(i + 1) % n];
      P2 s{b.x - a.x, b.y - a.y};
      for (const mpq_class& t : ts) {
        P2 q{a.x + t * s.x, a.y + t * s.y};
        mpq_class d = da + t * (db - da);
        LineView lv = look_along(c.sc, q, s);
        if (!lv.clean) continue;
        const LineItem* mine = nullptr;
        for (const LineItem& it : lv.items)
          if (it.kind != Kind::Intersection && it.depth == d) mine = &it;
        if (!mine || !mine->visible || !mine->drawn) continue;
        require_drawn(c, q, lv,
                      "the edge of face " + std::to_string(p.face) + " from " + str(a) + " to " + str(b) + " (" +
                          describe(mine->faces, mine->kind) + ")");
      }
    }
  }
}

// Where the planes of pieces p and r meet inside both projections: the
// midpoint of the first stretch of that line inside both (or nothing).
std::vector<P2> crossing_points(const Piece& p, const Piece& r, P2& dir) {
  std::vector<P2> out;
  mpq_class A = p.pa - r.pa, B = p.pb - r.pb, C = p.pc - r.pc;   // A x + B y + C = 0
  if (A == 0 && B == 0) return out;
  dir = P2{-B, A};
  mpq_class dd = A * A + B * B;
  P2 p0 = A != 0 ? P2{-C / A, 0} : P2{0, -C / B};
  auto param = [&](const P2& q) {
    mpq_class t = q.x * dir.x + q.y * dir.y;
    return t;
  };
  std::vector<mpq_class> ts;
  for (const Piece* pc : {&p, &r}) {
    for (std::size_t i = 0, n = pc->xy.size(); i < n; ++i) {
      const P2& u = pc->xy[i];
      const P2& v = pc->xy[(i + 1) % n];
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
  mpq_class t0 = param(p0);
  for (std::size_t k = 0; k + 1 < ts.size() && out.empty(); ++k) {
    mpq_class tm = (ts[k] + ts[k + 1]) / 2;
    mpq_class h = (tm - t0) / dd;
    P2 q{p0.x + dir.x * h, p0.y + dir.y * h};
    if (locate(q, p.xy) == Where::Inside && locate(q, r.xy) == Where::Inside) out.push_back(std::move(q));
  }
  return out;
}

void intersections(Context& c) {
  const auto& ps = c.sc.pieces;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps[i].orient == 0) continue;
    for (std::size_t j = i + 1; j < ps.size(); ++j) {
      const Piece& p = ps[i];
      const Piece& r = ps[j];
      if (r.orient == 0 || r.face == p.face || !p.box.meets(r.box)) continue;
      P2 dir;
      for (const P2& q : crossing_points(p, r, dir)) {
        LineView lv = look_along(c.sc, q, dir);
        if (!lv.clean) continue;
        std::vector<std::uint32_t> faces{std::min(p.face, r.face), std::max(p.face, r.face)};
        const LineItem* mine = nullptr;
        for (const LineItem& it : lv.items)
          if (it.kind == Kind::Intersection && it.faces == faces) mine = &it;
        if (!mine || !mine->visible || !mine->drawn) continue;
        require_drawn(c, q, lv, "the intersection of faces " + std::to_string(faces[0]) + " and " +
                                    std::to_string(faces[1]));
      }
    }
  }
}

}  // namespace

void check_coverage(Context& c) {
  edges(c);
  intersections(c);
}

}  // namespace vismap_check
