// The one dispatch on the engine: every caller that lets the user choose one
// comes through here, so that a new engine is added in one place.
#include "engine/visibility.h"

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

}  // namespace vismap
