#include "arrangements/map_builder.h"

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>

#include <algorithm>
#include <climits>
#include <map>
#include <numeric>
#include <stdexcept>

namespace vismap {
VISMAP_KERNEL_BEGIN
namespace {

using namespace exact;
using SegTraits = CGAL::Arr_segment_traits_2<K>;
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<SegTraits, int>;   // data: piece index
using Dcel = CGAL::Arr_extended_dcel<Traits, int, int, int>;   // vertex: point id; halfedge: attribute; face: index
using Arr = CGAL::Arrangement_2<Traits, Dcel>;
using Halfedge = Arr::Halfedge_const_handle;

// What an arrangement edge is, oriented along increasing (x, y).
struct EdgeAttr {
  bool drawn = false;
  EdgeKind kind = EdgeKind::Border;
  const std::vector<int>* faces = nullptr;
  int left = -1, right = -1;
  bool same_as(const EdgeAttr& o) const {
    if (drawn != o.drawn || left != o.left || right != o.right) return false;
    return !drawn || (kind == o.kind && *faces == *o.faces);
  }
};

struct UnionFind {
  std::vector<int> p;
  explicit UnionFind(std::size_t n) : p(n) { std::iota(p.begin(), p.end(), 0); }
  int find(int x) { while (p[x] != x) x = p[x] = p[p[x]]; return x; }
  void join(int a, int b) { p[find(a)] = find(b); }
};

FT depth_at(const MapPiece& m, const P2& p) {
  const bool use_x = CGAL::compare(CGAL::abs(m.b.x() - m.a.x()), CGAL::abs(m.b.y() - m.a.y())) != CGAL::SMALLER;
  FT lambda = use_x ? (p.x() - m.a.x()) / (m.b.x() - m.a.x()) : (p.y() - m.a.y()) / (m.b.y() - m.a.y());
  return m.za + lambda * (m.zb - m.za);
}

mpq_class signed_area2(const std::vector<Point2>& ring) {
  mpq_class s = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2 &p = ring[i], &q = ring[(i + 1) % ring.size()];
    s += p.x * q.y - q.x * p.y;
  }
  return s;
}

// Canonical start: the rotation that is lexicographically smallest.
void rotate_canonical(std::vector<Point2>& ring) {
  std::size_t best = 0;
  const std::size_t n = ring.size();
  for (std::size_t i = 1; i < n; ++i) {
    for (std::size_t k = 0; k < n; ++k) {
      const Point2 &a = ring[(i + k) % n], &b = ring[(best + k) % n];
      if (a < b) { best = i; break; }
      if (b < a) break;
    }
  }
  std::rotate(ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(best), ring.end());
}

bool ring_less(const std::vector<Point2>& a, const std::vector<Point2>& b) {
  return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end());
}

}  // namespace

void build_map(std::vector<MapPiece>& pieces, VisibilityMap& map) {
  // Orient every piece along increasing (x, y), as CGAL orients its edges.
  std::vector<Traits::Curve_2> curves;
  curves.reserve(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    MapPiece& m = pieces[i];
    if (m.b < m.a) { std::swap(m.a, m.b); std::swap(m.za, m.zb); std::swap(m.left, m.right); }
    curves.emplace_back(Seg2(m.a, m.b), static_cast<int>(i));
  }
  Arr arr;
  CGAL::insert(arr, curves.begin(), curves.end());

  // Edge attributes: the labels of any piece on it; where several drawn pieces
  // coincide, the first in (depth, face index) at the edge's midpoint is written.
  std::vector<EdgeAttr> attrs;
  attrs.reserve(arr.number_of_edges());
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    const auto& data = e->curve().data();
    EdgeAttr at;
    const MapPiece& any = pieces[data.front()];
    at.left = any.left;
    at.right = any.right;
    int winner = -1;
    P2 mid;
    bool have_mid = false;
    for (int pi : data) {
      const MapPiece& m = pieces[pi];
      if (!m.drawn) continue;
      if (winner < 0) { winner = pi; continue; }
      if (!have_mid) { mid = CGAL::midpoint(e->source()->point(), e->target()->point()); have_mid = true; }
      const MapPiece& w = pieces[winner];
      auto c = CGAL::compare(depth_at(m, mid), depth_at(w, mid));
      // Ties in (depth, lowest face index), e.g. two intersection lines of one face
      // along one 3D line: the faces lists, lexicographically, so that the written
      // segment does not depend on the order the pieces came in.
      if (c == CGAL::SMALLER ||
          (c == CGAL::EQUAL && (m.order_face < w.order_face ||
                                (m.order_face == w.order_face && *m.faces < *w.faces))))
        winner = pi;
    }
    if (winner >= 0) {
      at.drawn = true;
      at.kind = pieces[winner].kind;
      at.faces = pieces[winner].faces;
    }
    e->set_data(static_cast<int>(attrs.size()));
    e->twin()->set_data(static_cast<int>(attrs.size()));
    attrs.push_back(at);
  }

  // Face labels from the halfedges around them; they must all agree.
  int nfaces = 0;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) f->set_data(nfaces++);
  std::vector<int> label(nfaces, INT_MIN);
  label[arr.unbounded_face()->data()] = -1;
  auto implied = [&](Halfedge h) {
    const EdgeAttr& a = attrs[h->data()];
    return h->direction() == CGAL::ARR_LEFT_TO_RIGHT ? a.left : a.right;
  };
  for (auto h = arr.halfedges_begin(); h != arr.halfedges_end(); ++h) {
    int& l = label[h->face()->data()];
    int x = implied(h);
    if (l == INT_MIN) l = x;
    else if (l != x) throw std::logic_error("visibility map: inconsistent face labels (engine bug)");
  }

  // A vertex where two collinear edges of the same attributes meet is not a vertex.
  std::vector<Point2> points;
  for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) {
    bool essential = true;
    if (v->degree() == 2) {
      auto c = v->incident_halfedges();
      Halfedge h1 = c, h2 = ++c;
      if (attrs[h1->data()].same_as(attrs[h2->data()])) {
        const auto &d1 = h1->curve().data(), &d2 = h2->curve().data();
        bool share_piece = std::any_of(d1.begin(), d1.end(),
                                       [&](int p) { return std::find(d2.begin(), d2.end(), p) != d2.end(); });
        essential = !share_piece &&
                    CGAL::orientation(h1->source()->point(), v->point(), h2->source()->point()) != CGAL::COLLINEAR;
      }
    }
    if (!essential) { v->set_data(-1); continue; }
    v->set_data(static_cast<int>(points.size()));
    points.push_back(Point2{to_mpq(v->point().x()), to_mpq(v->point().y())});
  }

  // Regions: faces of one label joined across edges that separate nothing.
  UnionFind groups(nfaces);
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e)
    if (label[e->face()->data()] == label[e->twin()->face()->data()])
      groups.join(e->face()->data(), e->twin()->face()->data());
  auto boundary = [&](Halfedge h) { return label[h->face()->data()] != label[h->twin()->face()->data()]; };
  // A halfedge's index: its edge's, doubled, plus its direction (twins differ).
  auto index_of = [](Halfedge h) {
    return 2 * static_cast<std::size_t>(h->data()) + (h->direction() == CGAL::ARR_LEFT_TO_RIGHT ? 0 : 1);
  };
  std::vector<char> visited(2 * attrs.size(), 0);
  std::map<int, Region> regions;   // by group
  for (auto h0 = arr.halfedges_begin(); h0 != arr.halfedges_end(); ++h0) {
    const int lab = label[h0->face()->data()];
    if (lab < 0 || !boundary(h0) || visited[index_of(h0)]) continue;
    std::vector<Point2> ring;
    Halfedge h = h0;
    do {
      visited[index_of(h)] = 1;
      if (h->source()->data() >= 0) ring.push_back(points[h->source()->data()]);
      Halfedge nx = h->next();
      while (!boundary(nx)) nx = nx->twin()->next();   // step over edges inside the region
      h = nx;
    } while (h != Halfedge(h0));
    Region& r = regions[groups.find(h0->face()->data())];
    r.face = lab;
    rotate_canonical(ring);
    if (sgn(signed_area2(ring)) > 0) {
      if (!r.outer.empty()) throw std::logic_error("visibility map: region with two outer rings (engine bug)");
      r.outer = std::move(ring);
    } else {
      r.holes.push_back(std::move(ring));
    }
  }
  for (auto& [g, r] : regions) {
    if (r.outer.empty()) throw std::logic_error("visibility map: region without outer ring (engine bug)");
    std::sort(r.holes.begin(), r.holes.end(), ring_less);
    map.regions.push_back(std::move(r));
  }
  std::sort(map.regions.begin(), map.regions.end(), [](const Region& a, const Region& b) {
    if (a.face != b.face) return a.face < b.face;
    return ring_less(a.outer, b.outer);
  });

  // Segments: maximal chains of drawn edges through superfluous vertices.
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    if (!attrs[e->data()].drawn) continue;
    Halfedge h = e->direction() == CGAL::ARR_LEFT_TO_RIGHT ? Halfedge(e) : Halfedge(e->twin());
    if (h->source()->data() < 0) continue;   // not the start of its chain
    Halfedge cur = h;
    while (cur->target()->data() < 0) {
      auto c = cur->target()->incident_halfedges();
      Halfedge other = (Halfedge(c) == cur) ? Halfedge(++c) : Halfedge(c);
      cur = other->twin();
    }
    const EdgeAttr& a = attrs[e->data()];
    map.segments.push_back(Segment{points[h->source()->data()], points[cur->target()->data()], a.kind, *a.faces});
  }
  std::sort(map.segments.begin(), map.segments.end(), [](const Segment& a, const Segment& b) {
    if (a.from < b.from) return true;
    if (b.from < a.from) return false;
    return a.to < b.to;
  });
}

VISMAP_KERNEL_END

void build_map_from_floats(std::vector<FloatPiece>& pieces, VisibilityMap& map) {
  std::vector<MapPiece> mp;
  mp.reserve(pieces.size());
  for (const FloatPiece& f : pieces) {
    if (f.ax == f.bx && f.ay == f.by) continue;
    mp.push_back(MapPiece{exact::P2(f.ax, f.ay), exact::P2(f.bx, f.by), f.za, f.zb, f.left, f.right, f.drawn, f.kind,
                          f.faces, f.order_face});
  }
  build_map(mp, map);
}

}  // namespace vismap
