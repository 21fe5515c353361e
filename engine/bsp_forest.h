// Tomlinson 1982, "the priority of objects", over BSP trees: a scene of many
// objects is one small BSP tree per object (no object is cut by another's
// planes), and the objects are ordered per view from planes that separate them,
// found once. Objects that no plane separates (interpenetrating, or touching in
// a plane) are one group, one tree; groups that overlap on the screen in a cycle
// of priorities (Newell's three sticks, interlocking rings) are drawn by one
// tree of their union, made the first time a view needs it and kept: the cycle
// is broken by the splits of that tree. Internal to the engine (no CGAL type).
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "arrangements/visibility_map.h"
#include "engine/bsp_tree.h"

namespace vismap::engine {

// A plane with one group on one side (closed) and the other strictly on the
// other side: from an eye on one side, the group on that side is drawn last.
// Either an axis plane x_axis = c, or the plane through input vertex p with
// normal (q - p) x (s - r) (ids): a facet's plane (r = p, s a third corner), or
// the plane through an edge p-q of one group parallel to an edge r-s of the
// other (two convex objects apart are told apart by one or the other).
struct Separation {
  int axis = -1;                          // 0, 1, 2; -1: the plane through ids
  double c = 0;
  std::array<std::uint32_t, 4> ids{};     // p, q, r, s: x's side is the sign of det(q - p, s - r, x - p)
  int first_side = 0;                     // the side (+1 or -1) the lower-numbered group lies on
};

struct BspForest {
  std::shared_ptr<const WorldFacets> facets;
  std::vector<std::vector<std::uint32_t>> groups;   // each group's facets, ascending
  std::vector<std::uint32_t> group_of;              // each facet's group
  std::vector<BspTree> trees;                       // each group's
  std::vector<std::array<double, 6>> box;           // each group's vertices: x0, y0, z0, x1, y1, z1
  std::map<std::pair<int, int>, Separation> meeting;   // groups whose boxes meet: their plane
  std::map<std::vector<int>, BspTree> circuits;     // trees of groups drawn together (a cycle)
  std::shared_ptr<std::mutex> circuits_lock = std::make_shared<std::mutex>();   // (views side by side share them)
  std::int64_t objects = 0;                         // connected components (facets sharing vertices)
  exact::FilterCounts counted;                      // the filtered predicates making it ran (circuits' trees
                                                    // aside: each counts its own)
};

// The forest of the scene's facets. Throws InputError as make_world_facets does.
BspForest build_bsp_forest(const Scene& scene, int threads = 1);

// The trees to draw, back to front, for a view's eye: `screen[g]` bounds group g's
// occluding facets on the screen (x0, y0, x1, y1; x0 > x1 where it has none).
// Groups whose bounds overlap are ordered by their plane; each cycle of them
// is drawn by the tree of its union. Counts priority_pairs and
// priority_circuits into `stats`.
std::vector<const BspTree*> trees_back_to_front(BspForest& forest, const Scene& scene, const Eye& eye,
                                                const std::vector<std::array<double, 4>>& screen, Stats& stats);

}  // namespace vismap::engine
