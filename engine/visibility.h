// The engines' entry points: scene + view -> exact visibility map (Options, the
// library's, include/vismap/vismap.h).
#pragma once
#include <memory>
#include <vector>

#include "arrangements/visibility_map.h"
#include "engine/camera.h"
#include "engine/scene.h"

namespace vismap {

namespace engine {
struct BspForest;    // (engine/bsp_forest.h)
struct WorldScene;   // (engine/world_scene.h)
}  // namespace engine

// Franklin 1980: variable grid, exact predicates. The main engine. `world`, if
// given, is one make_world_scene made for this scene and kept by several views:
// what no camera changes is taken from it (the same map).
VisibilityMap visibility_franklin(const Scene& scene, const View& view,
                                  const Options& options, const engine::WorldScene* world = nullptr);

// The same code on plain doubles (CGAL::Simple_cartesian<double>), for the
// benchmarks only: it shows what exactness costs and buys, and may give a wrong
// map or throw std::logic_error where the doubles contradict each other.
VisibilityMap visibility_franklin_float(const Scene& scene, const View& view,
                                        const Options& options, const engine::WorldScene* world = nullptr);

// One fragment of Newell's ordered list: part of a face's projection, convex,
// counter-clockwise, exact.
struct PaintedFragment {
  int face = -1;
  std::vector<Point2> polygon;
};

// Newell, Newell & Sancha 1972: depth sort with plane splitting (the extended
// algorithm), then the fragments overlaid in drawing order. The second exact
// engine: the same map as visibility_franklin. If `painter` is given, it
// receives the fragments in drawing order, back to front.
VisibilityMap visibility_newell(const Scene& scene, const View& view, const Options& options,
                                std::vector<PaintedFragment>* painter = nullptr, const engine::WorldScene* world = nullptr);

// The BSP engine: the scene's forest (a BSP tree per group of objects and the
// planes that separate the groups, built once; `forest`, if given, is one
// build_bsp_forest made for this scene, shared by several views, which keeps
// the trees of cycles it meets) gives the drawing order from the eye; then
// Newell's overlay. The same map as the other two, in every view.
VisibilityMap visibility_bsp(const Scene& scene, const View& view, const Options& options,
                             std::vector<PaintedFragment>* painter = nullptr,
                             engine::BspForest* forest = nullptr, const engine::WorldScene* world = nullptr);

// The map by the engine options.algorithm names: the one place that dispatches
// (the library's compute, the command line, the fuzz harness and the stability
// stress call it). `painter`: as visibility_newell's, Newell's and the BSP engine only.
VisibilityMap compute_map(const Scene& scene, const View& view, const Options& options,
                          std::vector<PaintedFragment>* painter = nullptr);

// Many views of one scene: what does not depend on the camera is made once, on
// the first view (the world facets, their edge pieces and closed components;
// the BSP engine's forest), then each view's map, the same as compute_map's for
// that view. `views`: how many views will be asked for; one alone is made as
// compute_map makes it (nothing is kept).
class ViewSeries {
 public:
  ViewSeries(const Scene& scene, const Options& options, std::size_t views = 2);
  ~ViewSeries();
  VisibilityMap map(const View& view, std::vector<PaintedFragment>* painter = nullptr);

 private:
  const Scene& scene_;
  Options options_;
  bool keep_;
  std::unique_ptr<engine::WorldScene> world_;
  std::unique_ptr<engine::BspForest> forest_;
};

}  // namespace vismap
