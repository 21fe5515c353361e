// The visibility map as a plane graph, before it is written: the two ways of
// building it (CGAL's sweep in map_builder.cpp, direct assembly from pieces that
// meet only at their end points in map_assembly.cpp) fill this, and
// map_canonical.cpp labels its faces and writes regions and segments from it.
// Internal to the arrangements (kernel types).
#pragma once
#include <CGAL/Simple_cartesian.h>

#include <array>
#include <vector>

#include "arrangements/map_builder.h"
#include "engine/union_find.h"

namespace vismap {
VISMAP_KERNEL_BEGIN

// What an edge is, oriented from its lexicographically smaller end.
struct EdgeAttr {
  bool drawn = false;
  EdgeKind kind = EdgeKind::Border;
  const FacesList* faces = nullptr;
  int left = -1, right = -1;
  int line = -1;                // the curve of a piece on it (MapPiece::line; -1: not known):
                                // two edges with one curve are collinear, known without arithmetic
  bool same_as(const EdgeAttr& o) const {
    if (drawn != o.drawn || left != o.left || right != o.right) return false;
    return !drawn || (kind == o.kind && *faces == *o.faces);
  }
};

// The attributes of an edge from the pieces lying on it (oriented like the edge):
// the labels of any; where several visible pieces coincide, the first in (depth,
// face index, faces list) at the edge's midpoint decides: the edge is drawn with
// its kind and faces if it is drawn, and not drawn if it is not (a smooth seam).
EdgeAttr edge_attr(const std::vector<MapPiece>& pieces, const int* on_edge, std::size_t count,
                   const exact::P2& a, const exact::P2& b);

// Halfedge 2e runs u -> v along edge e = (u, v), u < v, with attrs[e].left on
// its left; halfedge 2e + 1 is its twin. Vertices are numbered in the
// lexicographic order of their points, so canonical order needs no coordinates.
struct MapGraph {
  using Approx = CGAL::Simple_cartesian<exact::Interval>::Point_2;
  std::vector<exact::P2> points;            // vertices, distinct, in lexicographic order
  std::vector<Approx> approx;               // their intervals, side by side: the walks over
                                            // the graph read these, not the lazy points
  void add_point(const exact::P2& p) {
    points.push_back(p);
    approx.push_back(p.approx());
  }
  std::vector<std::array<int, 2>> ends;     // edge -> (u, v)
  std::vector<EdgeAttr> attrs;              // edge -> attributes
  std::vector<int> next;                    // halfedge -> next halfedge around its face (face on the left)
  std::vector<int> face;                    // halfedge -> face id
  int faces = 0;                            // face ids 0 .. faces-1
  int unbounded = -1;                       // the unbounded face's id
};

// The direct assembly (assemble_map) in two halves. The graph's vertices and
// edges from the pieces, which it no longer needs once this returns (it keeps
// pointers to their faces lists); then the faces traced and labelled and the map
// written (throws std::logic_error where the pieces broke assemble_map's promise).
MapGraph graph_of_pieces(std::vector<MapPiece>& pieces, int threads);
void finish_map(MapGraph& g, VisibilityMap& map, int threads);

// Labels the faces (throws std::logic_error where the halfedges disagree: an
// engine bug), drops superfluous vertices, and writes the regions and segments
// into `map` in canonical order; the vertices' exact values on `threads` threads.
void write_canonical(const MapGraph& g, VisibilityMap& map, int threads = 1);

// The segments alone (no regions; map.has_regions false), as write_canonical
// writes them, from a graph that holds the drawn edges and every edge that
// bounds a region where it meets them: the faces' labels beyond are not needed.
void write_segments_only(const MapGraph& g, VisibilityMap& map, int threads = 1);

VISMAP_KERNEL_END
}  // namespace vismap
