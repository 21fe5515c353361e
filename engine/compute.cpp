// The one dispatch on the engine: every caller that lets the user choose one
// comes through here, so that a new engine is added in one place.
#include "engine/visibility.h"

#include <chrono>

#include "engine/bsp_forest.h"

namespace vismap {

VisibilityMap compute_map(const Scene& scene, const View& view, const Options& options,
                          std::vector<PaintedFragment>* painter) {
  switch (options.algorithm) {
    case Algorithm::Newell: return visibility_newell(scene, view, options, painter);
    case Algorithm::Bsp: return visibility_bsp(scene, view, options, painter);
    case Algorithm::Franklin: break;
  }
  return visibility_franklin(scene, view, options);
}

ViewSeries::ViewSeries(const Scene& scene, const Options& options) : scene_(scene), options_(options) {}
ViewSeries::~ViewSeries() = default;

VisibilityMap ViewSeries::map(const View& view, std::vector<PaintedFragment>* painter) {
  if (options_.algorithm != Algorithm::Bsp) return compute_map(scene_, view, options_, painter);
  double built = 0;   // (the first view's stats count the tree's making)
  if (!forest_) {
    const auto t0 = std::chrono::steady_clock::now();
    forest_ = std::make_unique<engine::BspForest>(engine::build_bsp_forest(scene_, options_.threads));
    built = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  VisibilityMap map = visibility_bsp(scene_, view, options_, painter, forest_.get());
  if (built > 0) map.stats.seconds.insert(map.stats.seconds.begin(), {"bsp_tree", built});
  return map;
}

}  // namespace vismap
