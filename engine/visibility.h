// The engines' entry points: scene + view -> exact visibility map.
#pragma once
#include "arrangements/visibility_map.h"
#include "engine/camera.h"
#include "engine/scene.h"

namespace vismap {

struct EngineOptions {
  double crease_deg = 30;   // dihedral angle above which a shared edge is a crease
  double grid_c = 4.0;      // Franklin's c in B = c * min(sqrt(N), 1/L)
  bool smooth = false;      // also draw smooth edges
};

// Franklin 1980: variable grid, exact predicates. The main engine.
VisibilityMap visibility_franklin(const Scene& scene, const View& view,
                                  const EngineOptions& options);

// The same code on plain doubles (CGAL::Simple_cartesian<double>), for the
// benchmarks only: it shows what exactness costs and buys, and may give a wrong
// map or throw std::logic_error where the doubles contradict each other.
VisibilityMap visibility_franklin_float(const Scene& scene, const View& view,
                                        const EngineOptions& options);

}  // namespace vismap
