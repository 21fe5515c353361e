// The engines' entry points: scene + view -> exact visibility map.
#pragma once
#include <vector>

#include "arrangements/visibility_map.h"
#include "engine/camera.h"
#include "engine/scene.h"

namespace vismap {

// Which engine computes the map; both give the same map.
enum class Algorithm { Franklin, Newell };

struct EngineOptions {
  double crease_deg = 30;   // dihedral angle above which a shared edge is a crease
  double grid_c = 4.0;      // Franklin's c in B = c * min(sqrt(N), 1/L)
  bool smooth = false;      // also draw smooth edges
  bool hidden = false;      // also the hidden lines (the map's `hidden` list)
  bool regions = true;      // false: the segments alone (a lines-only drawing), computing
                            // only what the drawn lines need; the map has no regions
  Algorithm algorithm = Algorithm::Franklin;   // for callers that dispatch (the CLI)
  int threads = 0;          // threads Franklin's engine may use (0: every usable core, one
                            // below 8192 faces); the map is the same, byte for byte, for every count
};

// Franklin 1980: variable grid, exact predicates. The main engine.
VisibilityMap visibility_franklin(const Scene& scene, const View& view,
                                  const EngineOptions& options);

// The same code on plain doubles (CGAL::Simple_cartesian<double>), for the
// benchmarks only: it shows what exactness costs and buys, and may give a wrong
// map or throw std::logic_error where the doubles contradict each other.
VisibilityMap visibility_franklin_float(const Scene& scene, const View& view,
                                        const EngineOptions& options);

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
VisibilityMap visibility_newell(const Scene& scene, const View& view, const EngineOptions& options,
                                std::vector<PaintedFragment>* painter = nullptr);

}  // namespace vismap
