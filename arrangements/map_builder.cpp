// Step 10 by CGAL's sweep: any pieces (they may cross and overlap), for Newell's
// engine and the float variant.
#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>

#include <algorithm>
#include <utility>

#include "arrangements/map_builder.h"
#include "arrangements/map_graph.h"

namespace vismap {
VISMAP_KERNEL_BEGIN
namespace {

using namespace exact;
using SegTraits = CGAL::Arr_segment_traits_2<K>;
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<SegTraits, int>;   // data: piece index
using Dcel = CGAL::Arr_extended_dcel<Traits, int, int, int>;   // vertex, edge, face: index in the MapGraph
using Arr = CGAL::Arrangement_2<Traits, Dcel>;
using Halfedge = Arr::Halfedge_const_handle;

}  // namespace

void build_map(std::vector<MapPiece>& pieces, VisibilityMap& map) {
  // Orient every piece along increasing (x, y), as CGAL orients its edges.
  std::vector<Traits::Curve_2> curves;
  curves.reserve(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    MapPiece& m = pieces[i];
    if (m.b < m.a) { std::swap(m.a, m.b); std::swap(m.left, m.right); }
    curves.emplace_back(Seg2(m.a, m.b), static_cast<int>(i));
  }
  Arr arr;
  CGAL::insert(arr, curves.begin(), curves.end());

  // The arrangement as a MapGraph: halfedge 2e runs left to right along edge e.
  MapGraph g;
  std::vector<Arr::Vertex_handle> vertices;
  for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) vertices.push_back(v);
  std::sort(vertices.begin(), vertices.end(), [](Arr::Vertex_handle a, Arr::Vertex_handle b) {
    return CGAL::compare_xy(a->point(), b->point()) == CGAL::SMALLER;
  });
  for (Arr::Vertex_handle v : vertices) {
    v->set_data(static_cast<int>(g.points.size()));
    g.add_point(v->point());
  }
  std::vector<int> on_edge;
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    Halfedge h = e->direction() == CGAL::ARR_LEFT_TO_RIGHT ? Halfedge(e) : Halfedge(e->twin());
    const auto& data = e->curve().data();
    on_edge.assign(data.begin(), data.end());
    e->set_data(static_cast<int>(g.ends.size()));
    e->twin()->set_data(static_cast<int>(g.ends.size()));
    g.ends.push_back({h->source()->data(), h->target()->data()});
    g.attrs.push_back(edge_attr(pieces, on_edge.data(), on_edge.size(), h->source()->point(), h->target()->point()));
  }
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) f->set_data(g.faces++);
  g.unbounded = arr.unbounded_face()->data();
  auto index_of = [](Halfedge h) { return 2 * h->data() + (h->direction() == CGAL::ARR_LEFT_TO_RIGHT ? 0 : 1); };
  g.next.resize(2 * g.ends.size());
  g.face.resize(2 * g.ends.size());
  for (auto h = arr.halfedges_begin(); h != arr.halfedges_end(); ++h) {
    g.next[index_of(h)] = index_of(h->next());
    g.face[index_of(h)] = h->face()->data();
  }
  write_canonical(g, map);
}

VISMAP_KERNEL_END

void build_map_from_floats(std::vector<FloatPiece>& pieces, VisibilityMap& map) {
  std::vector<MapPiece> mp;
  std::vector<exact::P3> ends;   // each piece's ends with depth: its line
  mp.reserve(pieces.size());
  ends.reserve(2 * pieces.size());   // (no reallocation: the pieces point into it)
  for (const FloatPiece& f : pieces) {
    if (f.ax == f.bx && f.ay == f.by) continue;
    ends.emplace_back(exact::FT(f.ax), exact::FT(f.ay), exact::FT(f.za));
    ends.emplace_back(exact::FT(f.bx), exact::FT(f.by), exact::FT(f.zb));
    mp.push_back(MapPiece{ends[ends.size() - 2].xy(), ends.back().xy(), &ends[ends.size() - 2], &ends.back(), f.left,
                          f.right, f.visible, f.drawn, f.kind, f.faces, f.order_face});
  }
  assemble_map(mp, map);
}

}  // namespace vismap
