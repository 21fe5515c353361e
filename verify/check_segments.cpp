// Check 6: every output segment is, at interior points, the visible line that
// is first in the order (depth, lowest face index), with its kind and faces.
// Also the topology: segments meet only at their endpoints, and no vertex is
// superfluous (the spec's canonical form).
#include <algorithm>
#include <map>
#include <numeric>

#include "verify/checks.h"
#include "verify/local.h"
#include "verify/rational.h"

namespace vismap_check {

std::string describe(const std::vector<std::uint32_t>& faces, Kind k) {
  std::string f;
  for (std::uint32_t i : faces) f += (f.empty() ? "" : ",") + std::to_string(i);
  return std::string(kind_name(k)) + " [" + f + "]";
}

std::vector<std::size_t> segments_at(const std::vector<MapSegment>& list, const BoxGrid& grid, const P2& q) {
  std::vector<std::size_t> out;
  for (std::uint32_t i : grid.near(q)) {
    const MapSegment& s = list[i];
    if (s.box.contains(q) && on_segment(q, s.from, s.to)) out.push_back(i);
  }
  return out;
}

std::string why_nothing(const LineView& lv) {
  auto first = lv.first_visible();
  if (!first.empty() && !first[0]->drawn)
    return "the first visible line there is not drawn (" + describe(first[0]->faces, first[0]->kind) + ")";
  const LineItem* hidden = nullptr;
  for (const LineItem& it : lv.items)
    if (it.drawn && !it.visible && !hidden) hidden = &it;
  if (hidden) return "the line there is hidden (" + describe(hidden->faces, hidden->kind) + ")";
  return "no edge piece or intersection line lies there";
}

std::vector<mpq_class> parameters() {
  std::vector<mpq_class> ts;
  for (unsigned d : {2u, 3u, 4u, 5u, 7u, 11u, 13u, 17u, 19u})
    for (unsigned n = 1; n < d; ++n)
      if (std::gcd(n, d) == 1) ts.emplace_back(n, d);
  return ts;
}

bool depth_line(const Context& c, const MapSegment& seg, const P2& s, mpq_class& da, mpq_class& db, bool hidden_only) {
  static const std::vector<mpq_class> ts = parameters();
  mpq_class t1, d1;
  bool have1 = false;
  for (const mpq_class& t : ts) {
    P2 q{seg.from.x + t * s.x, seg.from.y + t * s.y};
    LineView lv = look_along(c.sc, q, s);
    if (!lv.clean) continue;
    const LineItem* mine = nullptr;
    for (const LineItem& it : lv.items)
      if (it.kind == seg.kind && it.faces == seg.faces && !(hidden_only && it.visible) && (!mine || it.before(*mine)))
        mine = &it;
    if (!mine) continue;
    if (!have1) { t1 = t; d1 = mine->depth; have1 = true; continue; }
    const mpq_class k = (mine->depth - d1) / (t - t1);   // depth per unit of t
    da = d1 - k * t1;
    db = d1 + k * (1 - t1);
    return true;
  }
  return false;
}

namespace {

constexpr int kPointsPerSegment = 3;

// At a clean point q of the segment, its line must be the first visible drawn
// line there; false (and a failure recorded) if not.
bool first_at(Context& c, const MapSegment& seg, const std::string& name, const P2& q, const LineView& lv) {
  ++c.rep.segment_points_checked;
  auto first = lv.first();
  if (first.empty()) {
    c.fail.add("segment: " + name + " at " + str(q) + ": " + why_nothing(lv));
    return false;
  }
  bool match = false;
  for (const LineItem* it : first) match = match || (it->kind == seg.kind && it->faces == seg.faces);
  if (!match)
    c.fail.add("segment: " + name + " at " + str(q) + ": the first visible line there is " +
               describe(first[0]->faces, first[0]->kind));
  return match;
}

// Every stretch of the segment between points where what lies over it may change
// (where its line pierces a face's plane, crosses a projected edge...) must show
// the segment's line first: three sample points can all miss a short hidden part.
void check_whole(Context& c, const MapSegment& seg, const std::string& name) {
  const P2 s{seg.to.x - seg.from.x, seg.to.y - seg.from.y};
  mpq_class da, db;
  if (!depth_line(c, seg, s, da, db, /*hidden_only=*/false)) return;
  const std::vector<mpq_class> ts = stretch_params(c.sc, c.doc, seg.from, seg.to, da, db);
  for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
    const mpq_class t = (ts[k] + ts[k + 1]) / 2;
    P2 q{seg.from.x + t * s.x, seg.from.y + t * s.y};
    LineView lv = look_along(c.sc, q, s);
    if (lv.clean && !first_at(c, seg, name, q, lv)) return;
  }
}

}  // namespace

void check_segments(Context& c) {
  static const std::vector<mpq_class> ts = parameters();
  for (std::size_t si = 0; si < c.doc.segments.size(); ++si) {
    const MapSegment& seg = c.doc.segments[si];
    std::string name = "segments[" + std::to_string(si) + "] " + describe(seg);
    if (seg.kind == Kind::Smooth && !c.opt.smooth) c.fail.add("segment: " + name + ": smooth edges were not asked for");
    P2 s{seg.to.x - seg.from.x, seg.to.y - seg.from.y};
    int done = 0;
    bool failed = false;
    for (const mpq_class& t : ts) {
      P2 q{seg.from.x + t * s.x, seg.from.y + t * s.y};
      LineView lv = look_along(c.sc, q, s);
      if (!lv.clean) continue;
      if (!first_at(c, seg, name, q, lv)) { failed = true; break; }
      if (++done == kPointsPerSegment) break;
    }
    if (!failed) check_whole(c, seg, name);
  }
}

namespace {

struct P2Less {
  bool operator()(const P2& l, const P2& r) const { return l.x < r.x || (l.x == r.x && l.y < r.y); }
};

// The arrangement's edges leaving one vertex: directions, with the segment
// drawn along each (or none for an undrawn region boundary).
struct Star {
  std::vector<P2> dirs;
  std::vector<const MapSegment*> seg;
  void add(const P2& d, const MapSegment* s) {
    for (std::size_t i = 0; i < dirs.size(); ++i)
      if (cross_dir(dirs[i], d) == 0 && dirs[i].x * d.x + dirs[i].y * d.y > 0) {
        if (s) seg[i] = s;
        return;
      }
    dirs.push_back(d);
    seg.push_back(s);
  }
};

// The spec's canonical form: a vertex where exactly two edges meet, collinear,
// both drawn with the same kind and faces, or both undrawn, is no vertex.
void check_superfluous(Context& c) {
  std::map<P2, Star, P2Less> stars;
  auto dir = [](const P2& from, const P2& to) { return P2{to.x - from.x, to.y - from.y}; };
  for (const MapSegment& s : c.doc.segments) {
    stars[s.from].add(dir(s.from, s.to), &s);
    stars[s.to].add(dir(s.to, s.from), &s);
  }
  auto ring = [&](const std::vector<P2>& r) {
    for (std::size_t i = 0, n = r.size(); i < n; ++i) {
      stars[r[i]].add(dir(r[i], r[(i + 1) % n]), nullptr);
      stars[r[i]].add(dir(r[i], r[(i + n - 1) % n]), nullptr);
    }
  };
  for (const MapRegion& r : c.doc.regions) {
    ring(r.outer);
    for (const auto& h : r.holes) ring(h);
  }
  for (const auto& [v, st] : stars) {
    if (st.dirs.size() != 2 || cross_dir(st.dirs[0], st.dirs[1]) != 0) continue;
    const MapSegment* a = st.seg[0];
    const MapSegment* b = st.seg[1];
    if ((a == nullptr) != (b == nullptr)) continue;
    if (a && (a->kind != b->kind || a->faces != b->faces)) continue;
    c.fail.add("topology: superfluous vertex at " + str(v) + ": the map goes straight on there " +
               (a ? "with " + describe(a->faces, a->kind) + " on both sides" : std::string("along an undrawn boundary")));
  }
}

}  // namespace

void check_topology(Context& c) {
  check_superfluous(c);
  const auto& segs = c.doc.segments;
  std::vector<std::size_t> order(segs.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return segs[a].box.xmin < segs[b].box.xmin; });
  for (std::size_t i = 0; i < order.size(); ++i) {
    const MapSegment& a = segs[order[i]];
    for (std::size_t j = i + 1; j < order.size() && segs[order[j]].box.xmin <= a.box.xmax; ++j) {
      const MapSegment& b = segs[order[j]];
      if (!a.box.meets(b.box)) continue;
      P2 p;
      Meet m = meet(a.from, a.to, b.from, b.to, &p);
      std::string pair = "segments[" + std::to_string(order[i]) + "] and [" + std::to_string(order[j]) + "]";
      if (m == Meet::Overlap) {
        c.fail.add("topology: " + pair + " overlap (" + describe(a) + "; " + describe(b) + ")");
      } else if (m == Meet::Point) {
        bool end_a = p == a.from || p == a.to, end_b = p == b.from || p == b.to;
        if (!end_a || !end_b)
          c.fail.add("topology: " + pair + " meet at " + str(p) + ", not at an endpoint of both");
      }
    }
  }
}

}  // namespace vismap_check
