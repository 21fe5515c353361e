// vismap_check: an independent, brute-force, exact checker of vismap JSON maps.
// It shares nothing with the engine but the Scene struct: its own JSON parser,
// its own projection and clipping, GMP rationals for every decision (no doubles,
// no epsilons). See docs/format.md for the contract checked.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/scene.h"

namespace vismap_check {

struct Options {
  std::size_t samples = 2000;      // random sample points for the region check
  std::uint64_t seed = 1;          // deterministic (splitmix64)
  double crease_deg = 30;
  bool smooth = false;             // whether smooth edges are expected to be drawn
  // Stricter coverage: at every stretch of every edge and intersection line (no
  // shortcut over plainly hidden ones), the map must have a segment exactly where
  // the first visible line, recomputed from the spec's rule, is drawn.
  bool strict = false;
};

struct Report {
  bool ok = true;
  std::vector<std::string> failures;   // first ~20 failures, each with exact coordinates
  std::size_t samples_checked = 0, segment_points_checked = 0, edge_points_checked = 0;
};

// Checks that json_text is the exact visibility map of `scene` seen through the
// view matrix written in the JSON itself: the format; the regions at random
// points and by their exact total area; every segment at interior points; that
// every visible piece of every edge and intersection line is drawn (each cut
// where anything over it may change, every stretch tested); and the topology.
// Never throws; problems in the input are failures too.
Report check_map(const vismap::Scene& scene, const std::string& json_text, const Options& opt);

}  // namespace vismap_check
