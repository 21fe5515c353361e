// Franklin 1980, "A linear time exact hidden surface algorithm", step by step.
// Each step is one call; the steps live in screen_scene.cpp (1, culling),
// franklin_grid.cpp (2-9, 11) and arrangements/map_assembly.cpp (10).

#include "arrangements/map_builder.h"
#ifndef VISMAP_FLOAT_KERNEL
#include "arrangements/map_graph.h"   // (its graph has exact points)
#endif
#include "engine/franklin_grid.h"
#ifndef VISMAP_FLOAT_KERNEL
#include "engine/hidden_lines.h"
#endif
#include "engine/screen_scene.h"
#include "engine/engine_run.h"
#include "engine/parallel.h"
#include "engine/visibility.h"

namespace vismap {

#ifndef VISMAP_FLOAT_KERNEL
namespace {

// The vertex id of a piece's end point where it is one of its curve's ends (the
// very point object: a cut point equal to one is not looked for), else -1.
int vertex_id(const exact::P2& p, const engine::Curve& c) {
  if (exact::same_rep(p, c.s->xy())) return c.vs;
  if (exact::same_rep(p, c.t->xy())) return c.vt;
  return -1;
}

// Whether the curve lies on an upright screen line (its ends' x exactly equal):
// every point of it then has that x. (Uncounted: the threads share the ends.)
bool upright(const engine::Curve& c) { return exact::compare_uncounted(c.s->x, c.t->x) == CGAL::EQUAL; }

// What the assembly knows of a piece's ends without arithmetic: their vertex
// ids (MapPiece::ida, idb), and on an upright curve a cheap number equal to
// their x (xa, xb). (A vertex's own x is not given: the map writes every
// vertex's exact point, which the assembly then makes where x ties, as on a
// terrain's columns, at no extra cost.)
void name_ends(MapPiece& m, const engine::Curve& c) {
  m.ida = vertex_id(m.a, c);
  m.idb = vertex_id(m.b, c);
  if (upright(c)) m.xa = m.xb = &c.s->x;
}

// The classified pieces as the map takes them, each pointing at its curve's end
// points and faces list (in `faces`): a chunk of map pieces per chunk of pieces,
// on `threads` threads, each chunk freed once it is taken.
std::vector<MapPiece> map_pieces(engine::PieceChunks& pieces, const std::vector<engine::Curve>& curves,
                                 const std::vector<FacesList>& faces, int threads) {
  std::size_t total = 0;
  for (const std::vector<engine::VisiblePiece>& chunk : pieces) total += chunk.size();
  std::vector<MapPiece> mp;
  mp.reserve(total);
  engine::parallel_append(mp, static_cast<int>(pieces.size()), threads, [&](int k, std::vector<MapPiece>& out) {
    std::vector<engine::VisiblePiece>& chunk = pieces[static_cast<std::size_t>(k)];
    out.reserve(chunk.size());
    for (const engine::VisiblePiece& p : chunk) {
      const engine::Curve& c = curves[p.curve];
      out.push_back(MapPiece{p.a, p.b, c.s, c.t, p.left, p.right, p.visible, p.visible && c.drawn, c.kind,
                             &faces[p.curve], c.order_face, p.curve});
      name_ends(out.back(), c);
    }
    std::vector<engine::VisiblePiece>().swap(chunk);
  });
  engine::PieceChunks().swap(pieces);
  return mp;
}

}  // namespace
#endif

#ifdef VISMAP_FLOAT_KERNEL
#define VISMAP_FRANKLIN_ENTRY visibility_franklin_float
#else
#define VISMAP_FRANKLIN_ENTRY visibility_franklin
#endif
VisibilityMap VISMAP_FRANKLIN_ENTRY(const Scene& scene, const View& view, const Options& opt,
                                    const engine::WorldScene* world) {
  using namespace engine;
  VisibilityMap map = start_map(scene, view);
  Stats& st = map.stats;
  const exact::FilterCounts filter_before = exact::filter_counts;
  PhaseClock clock;
  Options run = opt;   // (with the thread count settled, for every step)
  const int threads = run.threads = thread_count(opt.threads, scene.faces.size());

  // 1. Project the scene exactly; skip what cannot be seen (outside, edge-on, back faces).
  // (For a lines-only drawing, curves that are not drawn stay latent until step 7.)
  ScreenScene ss = make_screen_scene(scene, view, run, st, /*latent=*/!opt.regions, /*cull=*/true, world);
  st.time("project_and_cull", clock.lap());
  // (A lines-only drawing that draws most edges anyway is made as a whole map
  // from here on, and only its segments written: make_screen_scene tells.)
  const bool whole = !ss.near_drawn_lines();

  // (Facets and curves are already in screen order: make_screen_scene.)
  // 2-4. The variable grid: B = c * min(sqrt(N), 1/L) cells per side.
  Grid grid = make_grid(ss, opt.grid_c, threads, st);
  // 5. Faces into cells, with each cell's blocking face; 5c drops faces hidden everywhere
  // (for a lines-only drawing, where no faces pierce each other: only near the drawn curves).
  bucket_facets(grid, ss, whole, threads, st);
  // 6. Remove what each cell's final blocking face hides.
  prune_facets(grid, ss, threads, st);
  st.time("faces_to_cells", clock.lap());

  // Faces that pierce each other draw an intersection line: a curve like any edge.
  add_intersection_lines(grid, ss, threads, st);
  std::vector<CellRange>().swap(grid.facet_range);   // (what the pair search needed of step 5)
  // 7. Edges into the cells they cross, unless behind the blocking face; 7b drops hidden ones
  // (for a lines-only drawing, edges that are not drawn only where a drawn one is).
  bucket_curves(grid, ss, whole, threads, st);
  if (ss.sparse()) st.count("image_bounds_made", std::count(ss.bounds_made.begin(), ss.bounds_made.end(), 1));
  st.time("edges_to_cells", clock.lap());

  // 8. Intersect the edges pairwise within each cell (for a lines-only drawing:
  // the pairs a drawn line's pieces depend on).
  Cuts cuts = cut_curves(grid, ss, whole, threads, st);
  st.time("intersections", clock.lap());

  // 9, 11. Cut edges into pieces; each piece's visibility, and the nearest face on each side.
  PieceChunks pieces = classify_pieces(grid, ss, cuts, threads, st);
  // The grid and the cut points have served: freed before the map is built, whose
  // graph is then the largest thing alive (10^6 faces: hundreds of MB less at the peak).
  grid = Grid();
  release(cuts.lists, threads);   // (millions of points on 10^5 squares: freed side by side)
  cuts = Cuts();
  st.time("visibility", clock.lap());

  // 10. The planar arrangement of the visible pieces, its regions labelled.
#ifdef VISMAP_FLOAT_KERNEL
  // The float variant's pieces go to the same assembly, on their doubles taken
  // as exact: where rounding made them cross or overlap in part (as on random
  // squares from 10^3 up), it refuses them (std::logic_error) instead of
  // writing a map that is wrong.
  std::vector<FloatPiece> mp;
  const std::vector<FacesList> faces = faces_lists(ss.curves);
  for (const std::vector<VisiblePiece>& chunk : pieces)
    for (const VisiblePiece& p : chunk) {
      const Curve& c = ss.curves[p.curve];
      mp.push_back(FloatPiece{p.a.x(), p.a.y(), p.b.x(), p.b.y(), depth_on(c, p.a), depth_on(c, p.b), p.left,
                              p.right, p.visible, p.visible && c.drawn, c.kind, &faces[p.curve], c.order_face});
    }
  build_map_from_floats(mp, map);
#else
  // The map needs the curves alone from here: the facets (and their depth
  // planes) are freed first. Each curve's faces list is kept for the map; the
  // curves go once the map pieces are made (these point at the curves' end
  // points and faces lists, not at the curves), before the graph is built.
  release(ss.facets, threads);
  std::vector<FacetBrief>().swap(ss.briefs);
  std::vector<std::uint32_t>().swap(ss.made_at);
  std::vector<std::vector<DepthPlane>>().swap(ss.planes);
  const std::vector<FacesList> faces = faces_lists(ss.curves, threads);
  std::vector<MapPiece> mp = map_pieces(pieces, ss.curves, faces, threads);
  release(ss.curves, threads);
  MapGraph graph = graph_of_pieces(mp, threads);
  // The graph holds what the map needs of the pieces (their faces lists aside):
  // they are freed before the faces are traced and the map is written, the
  // peak (10^6 faces: hundreds of MB less).
  release(mp, threads);
  if (opt.regions) finish_map(graph, map, threads);
  else write_segments_only(graph, map, threads);
  // What is left of the points (the map has their exact values), on the threads.
  release(graph.points, threads);
  release(ss.images, threads);
#endif
  unscale_map(map, ss.scale_exp);
  st.time("arrangement", clock.lap());
  st.count("visible_segments", static_cast<std::int64_t>(map.segments.size()));
  if (map.has_regions) st.count("regions", static_cast<std::int64_t>(map.regions.size()));
  // Exact work, to compare with the output's size: points the engine constructed
  // (intersection-line ends, crossings, piece midpoints), and the predicates the
  // interval filter could not settle (exact arithmetic decided them).
  st.count("constructed_points", 2 * st.counted("intersection_lines") + st.counted("intersections") +
                                     st.counted("pieces"));
  st.count("predicates", exact::filter_counts.calls - filter_before.calls);
  st.count("predicates_exact", exact::filter_counts.exact - filter_before.exact);
#ifndef VISMAP_FLOAT_KERNEL
  // The hidden lines, when asked: from the finished map (engine/hidden_lines.h).
  if (opt.hidden) add_hidden_lines(scene, view, run, map);
#endif
  return map;
}

}  // namespace vismap
