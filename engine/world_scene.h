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

}  // namespace vismap::engine
