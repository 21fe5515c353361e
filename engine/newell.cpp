// Newell, Newell & Sancha 1972, "A solution to the hidden surface problem",
// the extended algorithm, exact, with an exact overlay in place of the screen
// map. One call per step; the steps live in screen_scene.cpp (the shared front
// end), newell_order.cpp (the ordered list), newell_overlay.cpp (fragments ->
// pieces) and arrangements/map_assembly.cpp (the map). Stats follow the paper's
// Figure 2: faces in, faces considered, fragments written, and the time spent
// ordering and slicing and writing the fragments.
//
// The BSP engine (bsp.cpp) makes its drawing order from a tree and shares the
// rest: map_from_order below.

#include "arrangements/map_builder.h"
#include "engine/newell_order.h"
#include "engine/newell_overlay.h"
#include "engine/screen_scene.h"
#include "engine/engine_run.h"
#include "engine/threads.h"
#include "engine/hidden_lines.h"
#include "engine/visibility.h"

namespace vismap {

namespace engine {

void map_from_order(const Scene& scene, const View& view, const Options& opt, ScreenScene& ss,
                    const std::vector<Fragment>& order, VisibilityMap& map, PhaseClock& clock,
                    const exact::FilterCounts& filter_before, std::vector<PaintedFragment>* painter) {
  Stats& st = map.stats;
  // Writing the fragments, exactly: every line that may be drawn or bound a
  // region (intersection lines of piercing faces included) cut where anything on
  // it may change, each piece judged by what is painted beside and over it.
  add_piercing_lines(ss, st);
  drop_painted_over(ss, order, st);
  CutPoints cuts = cut_at_crossings(ss, st);
  st.time("intersections", clock.lap());
  const std::vector<FacesList> faces = faces_lists(ss.curves);   // (the map points at these)
  std::vector<MapPiece> pieces = paint_pieces(ss, order, cuts, faces, st);
  cuts = CutPoints();   // freed here, and counted here
  st.time("overlay", clock.lap());

  // The plane graph of the kept pieces, its regions labelled: assembled without
  // a sweep, since the pieces meet only at their end points (cut_at_crossings).
  assemble_map(pieces, map, thread_count(opt.threads, scene.faces.size()));
  unscale_map(map, ss.scale_exp);
  st.time("arrangement", clock.lap());
  st.count("visible_segments", static_cast<std::int64_t>(map.segments.size()));
  // (The overlay needs the whole map; a lines-only map just leaves out its regions.)
  if (opt.regions) st.count("regions", static_cast<std::int64_t>(map.regions.size()));
  else { map.regions.clear(); map.has_regions = false; }
  st.count("predicates", exact::filter_counts.calls - filter_before.calls);
  st.count("predicates_exact", exact::filter_counts.exact - filter_before.exact);
  // The hidden lines, when asked: from the finished map (engine/hidden_lines.h).
  if (opt.hidden) add_hidden_lines(scene, view, opt, map);

  if (painter) {
    painter->clear();
    painter->reserve(order.size());
    for (const Fragment& f : order) {
      PaintedFragment pf;
      pf.face = f.face;
      for (const exact::P3& p : f.v) {
        pf.polygon.push_back(Point2{exact::to_mpq(p.x), exact::to_mpq(p.y)});
        unscale(pf.polygon.back().x, ss.scale_exp);
        unscale(pf.polygon.back().y, ss.scale_exp);
      }
      painter->push_back(std::move(pf));
    }
  }
}

}  // namespace engine

VisibilityMap visibility_newell(const Scene& scene, const View& view, const Options& opt,
                                std::vector<PaintedFragment>* painter, const engine::WorldScene* world) {
  using namespace engine;
  VisibilityMap map = start_map(scene, view);
  Stats& st = map.stats;
  const exact::FilterCounts filter_before = exact::filter_counts;
  PhaseClock clock;

  // Transforming and initialising: project exactly, drop what cannot be seen
  // (outside, edge-on, back faces of closed solids), as Franklin's engine does.
  ScreenScene ss = make_screen_scene(scene, view, opt, st, /*latent=*/false, /*cull=*/true, world);
  st.time("project_and_cull", clock.lap());

  // Ordering and slicing faces: the list by farthest depth, the five tests,
  // reordering with marks, splitting by planes.
  std::vector<Fragment> order = depth_sort(ss, st);
  st.time("order_and_split", clock.lap());

  // Writing the fragments, the map, the hidden lines.
  map_from_order(scene, view, opt, ss, order, map, clock, filter_before, painter);
  return map;
}

}  // namespace vismap
