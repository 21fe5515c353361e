// The BSP engine: the scene's BSP tree (bsp_tree.cpp), built once in world
// space, gives the drawing order of a view; the fragments, projected exactly,
// are then overlaid as Newell's engine overlays its own (newell_overlay.cpp).
// One call per step.

#include <stdexcept>

#include "engine/bsp_tree.h"
#include "engine/engine_run.h"
#include "engine/newell_geometry.h"
#include "engine/newell_overlay.h"
#include "engine/screen_scene.h"
#include "engine/visibility.h"

namespace vismap {
namespace engine {
namespace {

// Each world facet's screen facet. The screen scene's facets are the same
// facets in screen order, which keeps the facets of one polygon in their order:
// the k-th screen facet of face F is F's k-th world facet.
std::vector<int> screen_facets(const BspTree& tree, const ScreenScene& ss) {
  const auto& wf = tree.facets.facets;
  std::vector<std::uint32_t> first, seen;   // each face's first world facet, and how many were seen
  int faces = 0;
  for (const WorldFacet& w : wf) faces = std::max(faces, w.face + 1);
  first.assign(static_cast<std::size_t>(faces) + 1, 0);
  for (const WorldFacet& w : wf) ++first[static_cast<std::size_t>(w.face) + 1];
  for (std::size_t f = 0; f < static_cast<std::size_t>(faces); ++f) first[f + 1] += first[f];
  seen.assign(static_cast<std::size_t>(faces), 0);
  std::vector<int> screen(wf.size(), -1);
  for (std::size_t fi = 0; fi < ss.facets.size(); ++fi) {
    const auto face = static_cast<std::size_t>(ss.facets[fi].face);
    screen[first[face] + seen[face]++] = static_cast<int>(fi);
  }
  return screen;
}

// The images of the tree's points in one view, made as fragments need them: an
// input vertex's is its facet's corner (the very same numbers: the overlay then
// knows it lies in the facet's plane without arithmetic); a split point's is
// a' + t (b' - a') of its segment's images, lazily (a parallel projection is
// affine: t is the world's), exact only if a predicate needs it.
class Images {
 public:
  explicit Images(const BspTree& tree) : tree_(tree), image_(tree.points.size()), made_(tree.points.size(), 0) {}

  const P3& of(std::uint32_t i, const Facet& F) {
    if (!made_[i]) {
      const BspTree::Point& p = tree_.points[i];
      if (p.vertex >= 0) {
        image_[i] = F.v[static_cast<std::size_t>(std::find(F.id.begin(), F.id.end(), p.vertex) - F.id.begin())];
      } else {
        const P3 &a = of(p.a, F), &b = of(p.b, F);
        const FT t(p.t);
        image_[i] = P3{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
      }
      made_[i] = 1;
    }
    return image_[i];
  }

 private:
  const BspTree& tree_;
  std::vector<P3> image_;
  std::vector<char> made_;
};

// The tree's fragments in drawing order, on the screen: those of occluding
// facets, counter-clockwise, as Newell's depth sort writes its own.
std::vector<Fragment> fragments_in_order(const BspTree& tree, const Scene& scene, const View& view,
                                         const ScreenScene& ss) {
  const std::vector<int> screen = screen_facets(tree, ss);
  Images images(tree);
  std::vector<Fragment> out;
  for (std::uint32_t xi : back_to_front(tree, scene, view)) {
    const BspTree::Fragment& x = tree.fragments[xi];
    const int fi = screen[x.facet];
    const Facet& F = ss.facets[static_cast<std::size_t>(fi)];
    if (!F.occluder) continue;
    Fragment f{fi, F.face, {}, {}, {}};
    for (std::uint32_t c : x.corners) {
      const P3& q = images.of(c, F);
      if (f.v.empty() || !(f.v.back().xy() == q.xy())) f.v.push_back(q);
    }
    while (f.v.size() > 1 && f.v.front().xy() == f.v.back().xy()) f.v.pop_back();
    if (F.facing == Facing::Back) std::reverse(f.v.begin(), f.v.end());   // counter-clockwise
    f.cut_on.assign(f.v.size(), -1);
    f.box = newell::box_of(f.v);
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace
}  // namespace engine

VisibilityMap visibility_bsp(const Scene& scene, const View& view, const Options& opt,
                             std::vector<PaintedFragment>* painter, const engine::BspTree* shared) {
  using namespace engine;
  if (view.perspective)
    throw std::invalid_argument("the BSP engine draws orthographic views only (a view direction, not an eye point)");
  VisibilityMap map = start_map(scene, view);
  Stats& st = map.stats;
  const exact::FilterCounts filter_before = exact::filter_counts;
  PhaseClock clock;

  // The tree: the caller's (built once for several views), or built now.
  BspTree own;
  if (!shared) own = build_bsp_tree(scene, opt.threads);
  const BspTree& tree = shared ? *shared : own;
  st.count("bsp_fragments", static_cast<std::int64_t>(tree.fragments.size()));
  st.count("bsp_splits", tree.splits);
  st.count("bsp_nodes", static_cast<std::int64_t>(tree.nodes.size()));
  st.count("bsp_depth", tree.depth);
  if (!shared) st.time("bsp_tree", clock.lap());   // (a shared tree's making is its maker's to count)
  else clock.lap();

  // Transforming and initialising, as the other engines do.
  ScreenScene ss = make_screen_scene(scene, view, opt, st);
  st.time("project_and_cull", clock.lap());

  // The drawing order: the tree traversed from the eye.
  std::vector<Fragment> order = fragments_in_order(tree, scene, view, ss);
  st.count("fragments_written", static_cast<std::int64_t>(order.size()));
  st.time("order", clock.lap());

  // Writing the fragments, the map, the hidden lines: as Newell's engine.
  map_from_order(scene, view, opt, ss, order, map, clock, filter_before, painter);
  return map;
}

}  // namespace vismap
