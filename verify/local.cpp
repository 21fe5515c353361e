// Brute force over all pieces at one point: O(pieces) per query, exact.
#include "verify/local.h"

#include <algorithm>
#include <map>

namespace vismap_check {

PointLabel label_at(const Screen& sc, const P2& q) {
  PointLabel out;
  struct Cand {
    const Piece* p;
    mpq_class d;
  };
  std::vector<Cand> cands;
  for (std::uint32_t pi : sc.grid.near(q)) {
    const Piece& p = sc.pieces[pi];
    if (!p.box.contains(q)) continue;
    Where w = locate(q, p);
    if (w == Where::Boundary) return out;   // on a projected edge (fan diagonals included)
    if (p.orient != 0 && w == Where::Inside) cands.push_back({&p, p.depth_at(q)});
  }
  const Cand* best = nullptr;
  for (const Cand& c : cands)
    if (!best || c.d < best->d || (c.d == best->d && c.p->face < best->p->face)) best = &c;
  if (best) {
    for (const Cand& c : cands)
      if (c.d == best->d && c.p->face != best->p->face && !c.p->same_plane(*best->p)) return out;
    out.face = best->p->face;
  }
  out.clean = true;
  return out;
}

std::vector<const LineItem*> LineView::first_visible() const {
  std::vector<const LineItem*> out;
  for (bool cuts : {false, true}) {
    const LineItem* best = nullptr;
    for (const LineItem& it : items)
      if (it.cut == cuts && it.visible && (!best || it.before(*best))) best = &it;
    if (!best) continue;
    for (const LineItem& it : items)
      if (it.cut == cuts && it.visible && it.same_key(*best)) out.push_back(&it);
    return out;
  }
  return out;
}

std::vector<const LineItem*> LineView::first() const {
  std::vector<const LineItem*> out = first_visible();
  if (!out.empty() && !out[0]->drawn) out.clear();
  return out;
}

LineView look_along(const Screen& sc, const P2& q, const P2& s) {
  LineView out;
  struct Hit {   // a piece's edge (or a face's plane) over q: depth there, slope along s
    const Piece* p;
    mpq_class depth, slope;
    int side = 0;   // edges and diagonals: +1 the piece lies left of s, -1 right
  };
  std::vector<Hit> edges, diags, covers, cuts;   // cuts: near-plane cuts (never lines)
  for (std::uint32_t pi : sc.grid.near(q)) {
    const Piece& p = sc.pieces[pi];
    if (!p.box.contains(q)) continue;
    const std::size_t n = p.xy.size();
    bool on_edge = false, inside = false;
    for (std::size_t i = 0; i < n; ++i) {
      const P2& a = p.xy[i];
      const P2& b = p.xy[p.next(i)];
      if (a == q) return out;   // a projected vertex
      if (!on_segment(q, a, b)) {
        // Even-odd parity, as in locate(), in the same pass.
        if ((a.y > q.y) != (b.y > q.y)) {
          int o = orient(a, b, q);
          if (b.y > a.y ? o > 0 : o < 0) inside = !inside;
        }
        continue;
      }
      P2 e{b.x - a.x, b.y - a.y};
      if (cross_dir(e, s) != 0) return out;   // an edge crossing the line
      on_edge = true;
      const mpq_class& da = p.depth[i];
      const mpq_class& db = p.depth[p.next(i)];
      mpq_class t = e.x != 0 ? mpq_class((q.x - a.x) / e.x) : mpq_class((q.y - a.y) / e.y);
      mpq_class k = s.x != 0 ? mpq_class(e.x / s.x) : mpq_class(e.y / s.y);   // e = k s
      Hit h{&p, da + t * (db - da), (db - da) / k};
      h.side = p.orient * sgn(k);   // a convex piece lies left of its edges when ccw
      if (p.role[i] == Role::Diagonal) {
        diags.push_back(std::move(h));
      } else if (p.role[i] == Role::Clip) {
        cuts.push_back(std::move(h));   // bounds the piece, but is no edge of its face
      } else {
        edges.push_back(std::move(h));
      }
    }
    if (!on_edge && inside && p.orient != 0) covers.push_back(Hit{&p, p.depth_at(q), p.slope_along(s)});
  }
  // A fanned face also covers q on a line where two of its triangles meet, one on
  // each side (not at a fold): a fan diagonal, or its own boundary where it runs
  // along itself (a corner repeated: a slit), since q is then inside the union of
  // its triangles. No plane: such covers make no intersection.
  std::vector<Hit> bent;
  std::vector<const Hit*> sides;
  for (const auto* v : {&diags, &edges})
    for (const Hit& h : *v)
      if (h.p->orient != 0) sides.push_back(&h);
  for (std::size_t i = 0; i < sides.size(); ++i) {
    for (std::size_t j = i + 1; j < sides.size(); ++j) {
      if (sides[j]->p->face != sides[i]->p->face || sides[j]->depth != sides[i]->depth) continue;
      if (sides[j]->side == -sides[i]->side) {
        bent.push_back(*sides[i]);
        break;
      }
    }
  }

  // Clean: any two things at the same depth over q agree along the line, so
  // the order of everything is the same on both sides of q.
  std::vector<const Hit*> all;
  for (const auto* v : {&edges, &diags, &covers, &cuts})
    for (const Hit& h : *v) all.push_back(&h);
  std::sort(all.begin(), all.end(), [](const Hit* a, const Hit* b) { return a->depth < b->depth; });
  for (std::size_t i = 1; i < all.size(); ++i)
    if (all[i]->depth == all[i - 1]->depth && all[i]->slope != all[i - 1]->slope) return out;
  out.clean = true;

  // Edge pieces: edges over q at the same depth (hence the same 3D line).
  std::vector<bool> used(edges.size(), false);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (used[i]) continue;
    std::map<std::uint32_t, const Piece*> owners;
    for (std::size_t j = i; j < edges.size(); ++j)
      if (!used[j] && edges[j].depth == edges[i].depth) {
        used[j] = true;
        owners.emplace(edges[j].p->face, edges[j].p);
      }
    LineItem it;
    std::vector<const Piece*> ps;
    for (const auto& [f, p] : owners) {
      it.faces.push_back(f);
      ps.push_back(p);
    }
    it.kind = edge_kind(ps, sc.cos_crease);
    it.depth = edges[i].depth;
    out.items.push_back(std::move(it));
  }
  // Near-plane cuts: a map may draw one as its face's border (the spec does not
  // say), but only where no edge piece or intersection line is visible.
  for (const Hit& h : cuts) {
    LineItem it;
    it.faces = {h.p->face};
    it.depth = h.depth;
    it.cut = true;
    out.items.push_back(std::move(it));
  }
  // Intersection lines: two faces' planes meeting over q along the line, away
  // from their edges (q inside both).
  for (std::size_t i = 0; i < covers.size(); ++i)
    for (std::size_t j = i + 1; j < covers.size(); ++j) {
      const Hit& a = covers[i];
      const Hit& b = covers[j];
      if (a.p->face == b.p->face || a.depth != b.depth || a.p->same_plane(*b.p)) continue;
      LineItem it;
      it.kind = Kind::Intersection;
      it.faces = {std::min(a.p->face, b.p->face), std::max(a.p->face, b.p->face)};
      it.depth = a.depth;
      bool dup = false;
      for (const LineItem& o : out.items) dup = dup || (o.kind == Kind::Intersection && o.faces == it.faces);
      if (!dup) out.items.push_back(std::move(it));
    }
  // Visibility: hidden by a face not sharing the line that comes before it.
  for (LineItem& it : out.items) {
    it.visible = true;
    for (const auto* v : {&covers, &bent})
      for (const Hit& c : *v) {
        std::uint32_t g = c.p->face;
        if (std::binary_search(it.faces.begin(), it.faces.end(), g)) continue;
        if (c.depth < it.depth || (c.depth == it.depth && g < it.faces[0])) it.visible = false;
      }
    it.drawn = it.kind != Kind::Smooth || sc.smooth;
  }
  return out;
}

}  // namespace vismap_check
