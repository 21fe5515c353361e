#include "engine/world_scene.h"

#include "engine/height_fields.h"

#include <algorithm>

namespace vismap::engine {

WorldScene make_world_scene(const Scene& scene, int threads) {
  const exact::FilterCounts before = exact::filter_counts;
  WorldScene w;
  w.wf = make_world_facets(scene, threads);
  std::vector<std::uint32_t> used, local;
  number_by_first_use(w.wf, scene.vertices.size(), used, local);
  MatchedSolids m = match_edges_and_solids(scene, w.wf, local, used.size(), /*ranked=*/true, threads);
  w.edges = std::move(m.edges);
  w.closed = std::move(m.closed);
  w.height_field = std::move(m.height_field);
  w.counted.calls = exact::filter_counts.calls - before.calls;
  w.counted.exact = exact::filter_counts.exact - before.exact;
  return w;
}

namespace {
MatchedSolids closed_and_height_fields(const Scene& scene, const WorldFacets& wf, MatchedEdges edges, int threads) {
  MatchedSolids m{std::move(edges), {}, {}};
  m.closed = closed_components(scene, wf, m.edges.pieces, threads);
  m.height_field = height_field_components(scene, wf, m.edges.pieces, m.closed.connected_components(), threads);
  return m;
}
}  // namespace

// (Vertex pairs: about a quarter of match_edges' cost, the 10^6-triangle
// terrain's 200 ms -> 55 ms.)
MatchedSolids match_edges_and_solids(const Scene& scene, const WorldFacets& wf, const std::vector<std::uint32_t>& local,
                                     std::size_t nused, bool ranked, int threads) {
  if (auto pairs = pieces_of_vertex_pairs(scene, wf, local, nused, threads)) {
    MatchedSolids m = closed_and_height_fields(scene, wf, MatchedEdges{std::move(*pairs), {}}, threads);
    const auto& label = m.height_field;
    if (std::all_of(label.begin(), label.end(), [&](int c) { return c >= 0 && c == label[0]; })) {
      if (ranked) m.edges.rank = vertex_pair_ranks(m.edges.pieces);
      return m;
    }
  }
  return closed_and_height_fields(scene, wf, match_edges_ranked(scene, wf, /*cell_bits=*/20, threads), threads);
}

}  // namespace vismap::engine
