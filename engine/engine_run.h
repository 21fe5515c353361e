// What both engines' drivers start with: the map's header filled from the scene
// and view, and a clock for the phase timings in the stats. No CGAL.
#pragma once
#include <chrono>
#include <cstdint>

#include "arrangements/visibility_map.h"
#include "engine/camera.h"
#include "engine/scene.h"

namespace vismap::engine {

// The map before any engine work: scene, projection, the exact view matrix and
// the count of faces read.
inline VisibilityMap start_map(const Scene& scene, const View& view) {
  VisibilityMap map;
  map.scene_file = scene.file;
  map.scene_faces = scene.faces.size();
  map.perspective = view.perspective;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) map.view[r][c] = mpq_class(view.m[r][c]);
  map.stats.count("faces_read", static_cast<std::int64_t>(scene.faces.size()));
  return map;
}

// x * 2^k, exactly.
inline void times_pow2(mpq_class& x, int k) {
  if (k > 0) mpq_mul_2exp(x.get_mpq_t(), x.get_mpq_t(), k);
  if (k < 0) mpq_div_2exp(x.get_mpq_t(), x.get_mpq_t(), -k);
}

// x / 2^k (the engines' screen scale, ScreenScene::scale_exp, undone).
inline void unscale(mpq_class& x, int k) { times_pow2(x, -k); }

// The finished map's vertices back in the spec's screen coordinates. (Scaling
// by a power of two keeps their lexicographic order: the map stays canonical.)
inline void unscale_map(VisibilityMap& map, int k) {
  if (k == 0) return;
  for (Point2& p : map.vertices) {
    unscale(p.x, k);
    unscale(p.y, k);
  }
}

// Seconds since the previous lap (or construction).
struct PhaseClock {
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  double lap() {
    auto t = std::chrono::steady_clock::now();
    double s = std::chrono::duration<double>(t - t0).count();
    t0 = t;
    return s;
  }
};

}  // namespace vismap::engine
