// The one dispatch on the engine: every caller that lets the user choose one
// comes through here, so that a new engine is added in one place.
#include "engine/visibility.h"

#include <chrono>

#include "engine/bsp_forest.h"
#include "engine/threads.h"
#include "engine/world_scene.h"

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

ViewSeries::ViewSeries(const Scene& scene, const Options& options, std::size_t views)
    : scene_(scene), options_(options), keep_(views > 1) {}
ViewSeries::~ViewSeries() = default;

VisibilityMap ViewSeries::map(const View& view, std::vector<PaintedFragment>* painter) {
  if (!keep_) return compute_map(scene_, view, options_, painter);
  // (The first view's stats count the making of what is kept.)
  std::vector<std::pair<std::string, double>> made;
  auto timed = [&](const char* name, auto&& make) {
    const auto t0 = std::chrono::steady_clock::now();
    make();
    made.emplace_back(name, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  };
  const int threads = engine::thread_count(options_.threads, scene_.faces.size());
  if (!world_)
    timed("world_scene", [&] { world_ = std::make_unique<engine::WorldScene>(engine::make_world_scene(scene_, threads)); });
  if (options_.algorithm == Algorithm::Bsp && !forest_)
    timed("bsp_tree", [&] { forest_ = std::make_unique<engine::BspForest>(engine::build_bsp_forest(scene_, options_.threads)); });
  VisibilityMap map;
  switch (options_.algorithm) {
    case Algorithm::Newell: map = visibility_newell(scene_, view, options_, painter, world_.get()); break;
    case Algorithm::Bsp: map = visibility_bsp(scene_, view, options_, painter, forest_.get(), world_.get()); break;
    case Algorithm::Franklin: map = visibility_franklin(scene_, view, options_, world_.get()); break;
  }
  map.stats.seconds.insert(map.stats.seconds.begin(), made.begin(), made.end());
  return map;
}

}  // namespace vismap
