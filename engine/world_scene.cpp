#include "engine/world_scene.h"

#include "engine/height_fields.h"

namespace vismap::engine {

WorldScene make_world_scene(const Scene& scene, int threads) {
  const exact::FilterCounts before = exact::filter_counts;
  WorldScene w;
  w.wf = make_world_facets(scene, threads);
  w.edges = match_edges_ranked(scene, w.wf, /*cell_bits=*/20, threads);
  w.closed = closed_components(scene, w.wf, w.edges.pieces, threads);
  w.height_field = height_field_components(scene, w.wf, w.edges.pieces, w.closed.connected_components(), threads);
  w.counted.calls = exact::filter_counts.calls - before.calls;
  w.counted.exact = exact::filter_counts.exact - before.exact;
  return w;
}

}  // namespace vismap::engine
