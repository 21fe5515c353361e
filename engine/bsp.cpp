// The BSP engine: the scene's forest (bsp_forest.cpp: a BSP tree per group of
// objects, and the planes that separate the groups), built once in world
// space, gives the drawing order of a view: the groups by priority, each by its
// tree; the fragments, projected exactly, are then overlaid as Newell's engine
// overlays its own (newell_overlay.cpp). One call per step.

#include <algorithm>
#include <cmath>
#include <optional>

#include "engine/bsp_forest.h"
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
std::vector<int> screen_facets(const WorldFacets& world, const ScreenScene& ss) {
  const auto& wf = world.facets;
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
// knows it lies in the facet's plane without arithmetic). A split point a + t (b
// - a) keeps t in homogeneous coordinates (the view is linear there): its image
// is made from a's and b's, lazily, exact only if a predicate needs it. (In an
// orthographic view W = 1: the screen point itself is a' + t (b' - a').)
class Images {
 public:
  Images(const BspTree& tree, const Scene& scene, const View& view, int scale_exp)
      : tree_(tree), scene_(scene), view_(view), scale_(std::ldexp(1.0, scale_exp)),
        image_(tree.points.size()), h_(view.perspective ? tree.points.size() : 0), made_(tree.points.size(), 0) {}

  // Whether point i is in front of the near plane (every point is, orthographically).
  bool in_front(std::uint32_t i, const Facet& F) {
    if (!view_.perspective) return true;
    const BspTree::Point& p = tree_.points[i];
    if (p.vertex >= 0) return F.has_vertex(p.vertex);   // (the facet keeps its corners in front)
    const Homogeneous& h = homogeneous(i);
    return CGAL::is_positive(h.Z) && CGAL::is_positive(h.W);
  }

  // The image of point i (in front).
  const P3& of(std::uint32_t i, const Facet& F) {
    if (made_[i]) return image_[i];
    const BspTree::Point& p = tree_.points[i];
    if (p.vertex >= 0) {
      image_[i] = F.v[static_cast<std::size_t>(std::find(F.id.begin(), F.id.end(), p.vertex) - F.id.begin())];
    } else if (!view_.perspective) {
      const P3 &a = of(p.a, F), &b = of(p.b, F);
      const FT t(p.t);
      image_[i] = P3{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
    } else {
      const Homogeneous& h = homogeneous(i);
      image_[i] = P3{scale_ * h.X / h.W, scale_ * h.Y / h.W, scale_ * h.Z / h.W};
    }
    made_[i] = 1;
    return image_[i];
  }

  // The image of the point where segment u-v (one end in front, one not) meets
  // the near plane Z = 0: depth 0 exactly, as the screen scene's cuts.
  P3 near_cut(std::uint32_t u, std::uint32_t v) {
    const Homogeneous &a = homogeneous(u), &b = homogeneous(v);
    const FT r = a.Z / (a.Z - b.Z);
    const FT X = a.X + r * (b.X - a.X), Y = a.Y + r * (b.Y - a.Y), W = a.W + r * (b.W - a.W);
    return P3{scale_ * X / W, scale_ * Y / W, FT(0)};
  }

 private:
  struct Homogeneous {
    FT X, Y, Z, W;
  };
  const BspTree& tree_;
  const Scene& scene_;
  const View& view_;
  FT scale_;
  std::vector<P3> image_;
  std::vector<std::optional<Homogeneous>> h_;   // (perspective only)
  std::vector<char> made_;

  const Homogeneous& homogeneous(std::uint32_t i) {
    std::optional<Homogeneous>& h = h_[i];
    if (h) return *h;
    const BspTree::Point& p = tree_.points[i];
    if (p.vertex >= 0) {
      const Vec3& w = scene_.vertices[static_cast<std::size_t>(p.vertex)];
      auto row = [&](int r) {
        const auto& m = view_.m[static_cast<std::size_t>(r)];
        return FT(m[0]) * FT(w.x) + FT(m[1]) * FT(w.y) + FT(m[2]) * FT(w.z) + FT(m[3]);
      };
      h = Homogeneous{row(0), row(1), row(2), row(3)};
    } else {
      const Homogeneous a = homogeneous(p.a), b = homogeneous(p.b);
      const FT t(p.t);
      h = Homogeneous{a.X + t * (b.X - a.X), a.Y + t * (b.Y - a.Y), a.Z + t * (b.Z - a.Z), a.W + t * (b.W - a.W)};
    }
    return *h;
  }
};

// Fragment x's edge labels (edges of its world facet w, or -1) as edges of w's
// screen facet F, as Newell's fragments and the curves' sharer_edge number them:
// the same where the near plane cuts nothing (else made in `relabelled`).
const std::vector<int>& screen_labels(const BspTree::Fragment& x, const WorldFacet& w, const Facet& F,
                                      std::vector<int>& relabelled) {
  if (std::find(F.id.begin(), F.id.end(), VertexId{-1}) == F.id.end()) return x.edge;
  const auto in_front = [&](std::uint32_t id) { return F.has_vertex(id); };   // (F keeps its corners in front)
  relabelled.assign(x.edge.size(), -1);
  for (std::size_t k = 0; k < x.edge.size(); ++k)
    if (x.edge[k] >= 0) relabelled[k] = screen_edge_of(w.v, x.edge[k], in_front);
  return relabelled;
}

// Fragment x of world facet w (screen facet F) on the screen, as `out`'s
// corners: those in front of the near plane and where its edges cross it,
// counter-clockwise, each edge with the facet edge it lies on (FragmentCorners).
// Empty where nothing of it is left.
void screen_polygon(const BspTree::Fragment& x, const WorldFacet& w, const Facet& F, Images& images,
                    Fragment& out) {
  FragmentCorners corners(out);
  const std::size_t n = x.corners.size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t a = x.corners[k], b = x.corners[(k + 1) % n];
    const bool fa = images.in_front(a, F), fb = images.in_front(b, F);
    if (fa) corners.add(images.of(a, F), on_corner(k, n));
    if (fa != fb) corners.add(fa ? images.near_cut(a, b) : images.near_cut(b, a), on_edge(k));
  }
  std::vector<int> relabelled;
  if (!corners.close(screen_labels(x, w, F, relabelled), F.facing == Facing::Back)) {
    out.v.clear();
    out.edge.clear();
  }
}

// Each group's bounds on the screen: its occluding facets' boxes (x0 > x1: none).
std::vector<std::array<double, 4>> group_bounds(const BspForest& forest, const std::vector<int>& screen,
                                                const ScreenScene& ss) {
  std::vector<std::array<double, 4>> b(forest.groups.size(), {HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL});
  for (std::size_t w = 0; w < screen.size(); ++w) {
    const Facet& F = ss.facets[static_cast<std::size_t>(screen[w])];
    if (!F.occluder) continue;
    auto& g = b[forest.group_of[w]];
    g = {std::min(g[0], F.box.xmin()), std::min(g[1], F.box.ymin()), std::max(g[2], F.box.xmax()),
         std::max(g[3], F.box.ymax())};
  }
  return b;
}

// One tree's fragments in drawing order, on the screen, appended to `out`:
// those of occluding facets, as Newell's depth sort writes its own.
void append_fragments(const BspTree& tree, const Scene& scene, const View& view, const Eye& eye,
                      const ScreenScene& ss, const std::vector<int>& screen, std::vector<Fragment>& out) {
  Images images(tree, scene, view, ss.scale_exp);
  for (std::uint32_t xi : back_to_front(tree, scene, eye)) {
    const BspTree::Fragment& x = tree.fragments[xi];
    const int fi = screen[x.facet];
    const Facet& F = ss.facets[static_cast<std::size_t>(fi)];
    if (!F.occluder) continue;
    Fragment f{fi, F.face, {}, {}, {}, {}};
    screen_polygon(x, tree.facets->facets[x.facet], F, images, f);
    if (f.v.empty()) continue;
    f.cut_on.assign(f.v.size(), -1);
    f.box = newell::box_of(f.v);
    out.push_back(std::move(f));
  }
}

// The forest's fragments in drawing order: the groups by priority, each by its tree.
std::vector<Fragment> fragments_in_order(BspForest& forest, const Scene& scene, const View& view,
                                         const ScreenScene& ss, Stats& stats) {
  const std::vector<int> screen = screen_facets(*forest.facets, ss);
  const Eye eye = eye_of(view);   // (once: every tree and every pair of groups asks it)
  std::vector<Fragment> out;
  for (const BspTree* tree : trees_back_to_front(forest, scene, eye, group_bounds(forest, screen, ss), stats))
    append_fragments(*tree, scene, view, eye, ss, screen, out);
  return out;
}

// The forest's size: objects, groups, and the groups' trees' fragments, splits,
// nodes and depth (not the trees of circuits, made as views need them).
void count_forest(const BspForest& forest, Stats& st) {
  std::int64_t fragments = 0, splits = 0, nodes = 0;
  int depth = 0;
  for (const BspTree& t : forest.trees) {
    fragments += static_cast<std::int64_t>(t.fragments.size());
    splits += t.splits;
    nodes += static_cast<std::int64_t>(t.nodes.size());
    depth = std::max(depth, t.depth);
  }
  st.count("bsp_objects", forest.objects);
  st.count("bsp_groups", static_cast<std::int64_t>(forest.groups.size()));
  st.count("bsp_fragments", fragments);
  st.count("bsp_splits", splits);
  st.count("bsp_nodes", nodes);
  st.count("bsp_depth", depth);
}

}  // namespace
}  // namespace engine

VisibilityMap visibility_bsp(const Scene& scene, const View& view, const Options& opt,
                             std::vector<PaintedFragment>* painter, engine::BspForest* shared,
                             const engine::WorldScene* world) {
  using namespace engine;
  VisibilityMap map = start_map(scene, view);
  Stats& st = map.stats;
  const exact::FilterCounts filter_before = exact::filter_counts;
  PhaseClock clock;

  // The forest: the caller's (built once for several views), or built now.
  BspForest own;
  if (!shared) own = build_bsp_forest(scene, opt.threads);
  BspForest& forest = shared ? *shared : own;
  if (shared) {   // (made once for several views: counted as if made for this one)
    exact::filter_counts.calls += forest.counted.calls;
    exact::filter_counts.exact += forest.counted.exact;
  }
  count_forest(forest, st);
  if (!shared) st.time("bsp_tree", clock.lap());   // (a shared forest's making is its maker's to count)
  else clock.lap();

  // Transforming and initialising, as the other engines do.
  ScreenScene ss = make_screen_scene(scene, view, opt, st, /*latent=*/false, /*cull=*/true, world);
  st.time("project_and_cull", clock.lap());

  // The drawing order: the groups by priority, each tree traversed from the eye.
  std::vector<Fragment> order = fragments_in_order(forest, scene, view, ss, st);
  st.count("fragments_written", static_cast<std::int64_t>(order.size()));
  st.time("order", clock.lap());

  // Writing the fragments, the map, the hidden lines: as Newell's engine.
  map_from_order(scene, view, opt, ss, order, map, clock, filter_before, painter);
  return map;
}

}  // namespace vismap
