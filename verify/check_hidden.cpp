// Check 8, where the map has "hidden" (spec: *hidden*). From the spec's words:
// a point of a drawn edge piece or intersection line is hidden where it is not
// visible and no visible segment lies over it; coinciding hidden pieces give one
// segment, with the kind and faces of the one first in (depth, face index);
// hidden segments never overlap each other or a visible segment, and each is a
// maximal stretch of one kind and faces list.
//   - every hidden segment, at sample points and at every stretch between points
//     where what lies over it may change, is such a hidden line;
//   - every edge and intersection line, at every such stretch where it is drawn
//     and not visible and no visible segment covers it, has a hidden segment of
//     the first hidden line's kind and faces;
//   - no two hidden segments overlap, and none goes straight on into another of
//     the same kind and faces (not maximal).
#include <algorithm>
#include <map>

#include "verify/checks.h"
#include "verify/local.h"
#include "verify/rational.h"

namespace vismap_check {
namespace {

constexpr int kPointsPerSegment = 3;

std::string name_of(const MapDoc& doc, std::size_t i) {
  return "hidden[" + std::to_string(i) + "] " + describe(doc.hidden[i]);
}

// Hidden segments whose closed extent holds q.
std::vector<std::size_t> hidden_at(const MapDoc& doc, const P2& q) { return segments_at(doc.hidden, doc.hidden_grid, q); }

// The hidden lines at q first in the order (depth, face index): drawn lines
// (edge pieces and intersection lines, not near-plane cuts) that are not
// visible there. Several only on exact ties.
std::vector<const LineItem*> first_hidden(const LineView& lv) {
  auto hidden = [](const LineItem& it) { return it.drawn && !it.visible && !it.cut; };
  const LineItem* best = nullptr;
  for (const LineItem& it : lv.items)
    if (hidden(it) && (!best || it.before(*best))) best = &it;
  std::vector<const LineItem*> out;
  for (const LineItem& it : lv.items)
    if (best && hidden(it) && it.same_key(*best)) out.push_back(&it);
  return out;
}

bool matches(const std::vector<const LineItem*>& items, const MapSegment& s) {
  for (const LineItem* it : items)
    if (it->kind == s.kind && it->faces == s.faces) return true;
  return false;
}

// At a clean point q of hidden segment h: no visible segment over it, and a
// hidden line there, the first of which has h's kind and faces.
bool hidden_ok_at(Context& c, const MapSegment& h, const std::string& name, const P2& q, const LineView& lv) {
  ++c.rep.segment_points_checked;
  const std::vector<std::size_t> over = segments_at(c.doc, q);
  if (!over.empty()) {
    c.fail.add("hidden: " + name + " at " + str(q) + ": a visible segment lies over it (segments[" +
               std::to_string(over[0]) + "] " + describe(c.doc.segments[over[0]]) + ")");
    return false;
  }
  const std::vector<const LineItem*> first = first_hidden(lv);
  if (first.empty()) {
    bool visible = false;
    for (const LineItem& it : lv.items) visible = visible || (it.drawn && it.visible && !it.cut);
    c.fail.add("hidden: " + name + " at " + str(q) + ": " +
               (visible ? std::string("the line there is visible")
                        : std::string("no hidden edge piece or intersection line lies there")));
    return false;
  }
  if (!matches(first, h)) {
    c.fail.add("hidden: " + name + " at " + str(q) + ": the first hidden line there is " +
               describe(first[0]->faces, first[0]->kind));
    return false;
  }
  return true;
}

// Parameters of the hidden segments' end points on the closed segment a -> b.
void add_hidden_ends(const MapDoc& doc, const P2& a, const P2& b, std::vector<mpq_class>& ts) {
  const P2 s{b.x - a.x, b.y - a.y};
  const mpq_class ss = s.x * s.x + s.y * s.y;
  const Box box = box_of(a, b);
  for (const MapSegment& h : doc.hidden) {
    if (!h.box.meets(box)) continue;
    for (const P2* p : {&h.from, &h.to}) {
      if (!on_segment(*p, a, b)) continue;
      mpq_class t = ((p->x - a.x) * s.x + (p->y - a.y) * s.y) / ss;
      if (t > 0 && t < 1) ts.push_back(std::move(t));
    }
  }
  std::sort(ts.begin(), ts.end());
  ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
}

void check_segment(Context& c, std::size_t i) {
  static const std::vector<mpq_class> ts = parameters();
  const MapSegment& h = c.doc.hidden[i];
  const std::string name = name_of(c.doc, i);
  if (h.kind == Kind::Smooth && !c.opt.smooth) {
    c.fail.add("hidden: " + name + ": smooth edges were not asked for");
    return;
  }
  const P2 s{h.to.x - h.from.x, h.to.y - h.from.y};
  int done = 0;
  for (const mpq_class& t : ts) {
    const P2 q{h.from.x + t * s.x, h.from.y + t * s.y};
    const LineView lv = look_along(c.sc, q, s);
    if (!lv.clean) continue;
    if (!hidden_ok_at(c, h, name, q, lv)) return;
    if (++done == kPointsPerSegment) break;
  }
  // Every stretch: three points can miss a short visible or covered part.
  mpq_class da, db;
  if (!depth_line(c, h, s, da, db, /*hidden_only=*/true)) return;
  std::vector<mpq_class> cut = stretch_params(c.sc, c.doc, h.from, h.to, da, db);
  add_hidden_ends(c.doc, h.from, h.to, cut);
  for (std::size_t k = 0; k + 1 < cut.size(); ++k) {
    const mpq_class t = (cut[k] + cut[k + 1]) / 2;
    const P2 q{h.from.x + t * s.x, h.from.y + t * s.y};
    const LineView lv = look_along(c.sc, q, s);
    if (lv.clean && !hidden_ok_at(c, h, name, q, lv)) return;
  }
}

// Where the spec's first hidden line at q exists and no visible segment covers
// q, a hidden segment must lie there with its kind and faces.
void require_hidden(Context& c, const P2& q, const LineView& lv, const std::string& what) {
  ++c.rep.edge_points_checked;
  const std::vector<const LineItem*> first = first_hidden(lv);
  if (first.empty() || !segments_at(c.doc, q).empty()) return;
  const std::vector<std::size_t> at = hidden_at(c.doc, q);
  if (at.empty()) {
    c.fail.add("hidden coverage: no hidden segment at " + str(q) + " where " + what + " is hidden (" +
               describe(first[0]->faces, first[0]->kind) + " first)");
    return;
  }
  if (at.size() > 1) return;   // overlapping hidden segments: reported below
  if (!matches(first, c.doc.hidden[at[0]]))
    c.fail.add("hidden coverage: " + name_of(c.doc, at[0]) + " at " + str(q) + ": the first hidden line there is " +
               describe(first[0]->faces, first[0]->kind));
}

// Calls f(q) at the midpoint of every stretch of a -> b (depth da -> db), cut
// where anything over it may change and at the hidden segments' ends.
template <class F>
void for_each_stretch(const Context& c, const P2& a, const P2& b, const mpq_class& da, const mpq_class& db, F&& f) {
  std::vector<mpq_class> ts = stretch_params(c.sc, c.doc, a, b, da, db);
  add_hidden_ends(c.doc, a, b, ts);
  for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
    const mpq_class t = (ts[k] + ts[k + 1]) / 2;
    f(P2{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)}, da + t * (db - da));
  }
}

void cover_edges(Context& c) {
  for (const Piece& p : c.sc.pieces) {
    for (std::size_t i = 0, n = p.xy.size(); i < n; ++i) {
      if (p.role[i] != Role::Boundary) continue;
      const P2& a = p.xy[i];
      const P2& b = p.xy[p.next(i)];
      if (a == b) continue;
      const P2 s{b.x - a.x, b.y - a.y};
      for_each_stretch(c, a, b, p.depth[i], p.depth[p.next(i)], [&](const P2& q, const mpq_class& d) {
        const LineView lv = look_along(c.sc, q, s);
        if (!lv.clean) return;
        const LineItem* mine = nullptr;
        for (const LineItem& it : lv.items)
          if (it.kind != Kind::Intersection && !it.cut && it.depth == d) mine = &it;
        if (!mine || !mine->drawn || mine->visible) return;
        require_hidden(c, q, lv,
                       "the edge of face " + std::to_string(p.face) + " from " + str(a) + " to " + str(b));
      });
    }
  }
}

void cover_intersections(Context& c) {
  for_each_crossing(c.sc, [&](const std::vector<std::uint32_t>& faces, const Piece& p, const P2& a, const P2& b,
                              const P2& dir) {
    for_each_stretch(c, a, b, p.depth_at(a), p.depth_at(b), [&](const P2& q, const mpq_class&) {
      const LineView lv = look_along(c.sc, q, dir);
      if (!lv.clean) return;
      const LineItem* mine = nullptr;
      for (const LineItem& it : lv.items)
        if (it.kind == Kind::Intersection && it.faces == faces) mine = &it;
      if (!mine || !mine->drawn || mine->visible) return;
      require_hidden(c, q, lv,
                     "the intersection of faces " + std::to_string(faces[0]) + " and " + std::to_string(faces[1]));
    });
  });
}

struct P2Less {
  bool operator()(const P2& l, const P2& r) const { return l.x < r.x || (l.x == r.x && l.y < r.y); }
};

// No two hidden segments overlap; none goes straight on, at an end, into
// another of the same kind and faces (the two would be one maximal segment).
void hidden_topology(Context& c) {
  const auto& hs = c.doc.hidden;
  std::map<P2, std::vector<std::size_t>, P2Less> ends;
  for (std::size_t i = 0; i < hs.size(); ++i) {
    ends[hs[i].from].push_back(i);
    ends[hs[i].to].push_back(i);
  }
  for (const auto& [v, at] : ends)
    for (std::size_t x = 0; x < at.size(); ++x)
      for (std::size_t y = x + 1; y < at.size(); ++y) {
        const MapSegment& a = hs[at[x]];
        const MapSegment& b = hs[at[y]];
        if (a.kind != b.kind || a.faces != b.faces) continue;
        const P2& fa = a.from == v ? a.to : a.from;
        const P2& fb = b.from == v ? b.to : b.from;
        const P2 da{fa.x - v.x, fa.y - v.y}, db{fb.x - v.x, fb.y - v.y};
        if (cross_dir(da, db) == 0 && da.x * db.x + da.y * db.y < 0)
          c.fail.add("hidden: " + name_of(c.doc, at[x]) + " and hidden[" + std::to_string(at[y]) +
                     "] go straight on at " + str(v) + " with one kind and faces: not maximal");
      }
  std::vector<std::size_t> order(hs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return hs[a].box.xmin < hs[b].box.xmin; });
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1; j < order.size() && hs[order[j]].box.xmin <= hs[order[i]].box.xmax; ++j) {
      const MapSegment& a = hs[order[i]];
      const MapSegment& b = hs[order[j]];
      if (a.box.meets(b.box) && meet(a.from, a.to, b.from, b.to) == Meet::Overlap)
        c.fail.add("hidden: " + name_of(c.doc, order[i]) + " and hidden[" + std::to_string(order[j]) + "] overlap");
    }
}

}  // namespace

void check_hidden(Context& c) {
  hidden_topology(c);
  for (std::size_t i = 0; i < c.doc.hidden.size(); ++i) check_segment(c, i);
  cover_edges(c);
  cover_intersections(c);
}

}  // namespace vismap_check
