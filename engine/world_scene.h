// What no camera changes, made once for many views of one scene (ViewSeries):
// the world facets, the edge pieces matched on them, and the closed components
// that culling asks about. Each view then takes them in the order it sees the
// facets (make_screen_scene): a renumbered copy, not a new matching.
#pragma once
#include "engine/culling.h"
#include "engine/edge_pieces.h"
#include "engine/exact_kernel.h"
#include "engine/world_facets.h"

namespace vismap::engine {

struct WorldScene {
  WorldFacets wf;               // in the input's order
  MatchedEdges edges;           // matched on wf
  ClosedComponents closed;      // on wf and edges
  std::vector<int> height_field;   // per facet of wf: engine/height_fields.h
  // The filtered predicates making these took: each view counts them, as a
  // view made alone does (its stats are then the same).
  exact::FilterCounts counted;
};

WorldScene make_world_scene(const Scene& scene, int threads = 1);

// The edge pieces of wf and the closed components and height fields they make.
// A surface that vertex pairs alone may match (pieces_of_vertex_pairs: a disk
// of triangles) is matched so first; if those pieces make every facet one
// height field, its certificate says that the surface's projection is one to
// one, so no vertex lies inside an edge, and they are the pieces. Else the
// edges are matched geometrically (match_edges_ranked). The same pieces either
// way, and so the same maps. local, nused: the vertices numbered in the order
// wf's facets first use them (number_by_first_use). Ranks only where `ranked`
// (else edges.rank may be empty).
struct MatchedSolids {
  MatchedEdges edges;
  ClosedComponents closed;
  std::vector<int> height_field;
};
MatchedSolids match_edges_and_solids(const Scene& scene, const WorldFacets& wf, const std::vector<std::uint32_t>& local,
                                     std::size_t nused, bool ranked, int threads = 1);

}  // namespace vismap::engine
