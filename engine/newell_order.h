// Newell, Newell & Sancha 1972, "the extended algorithm": the occluding facets as
// a list of convex fragments in drawing order (back to front), so that painting
// them in that order paints the right face everywhere. Internal to the engine.
#pragma once
#include <vector>

#include "engine/part_edges.h"
#include "engine/screen_scene.h"

namespace vismap::engine {

// A piece of one facet: convex, counter-clockwise on the screen, in its facet's
// plane (z = the facet's depth there), no two equal consecutive vertices.
struct Fragment {
  int facet = -1;                // index in ScreenScene::facets
  int face = -1;                 // input face index
  std::vector<P3> v;
  std::vector<int> cut_on;       // per vertex: the facet on whose plane it was cut, or -1
  std::vector<int> edge;         // per edge v[k] -> v[k+1]: the edge j of its facet (Facet::v[j] ->
                                 // v[j+1]) whose line holds it, or -1 (a cut, or not known)
  CGAL::Bbox_2 box;              // contains the exact projection
};

// A fragment's screen polygon made corner by corner, each corner with the edges of
// its source polygon it lies on (part_edges.h bits). A corner equal on the screen
// to the one before it is left out: the corner kept lies on the edges of both.
class FragmentCorners {
 public:
  explicit FragmentCorners(Fragment& f) : f_(f) {}
  void add(const P3& p, std::uint64_t edges);
  // Closes the polygon (its last corner equal to its first is left out too) and
  // labels its edges from the source polygon's `labels`, reversed to run
  // counter-clockwise where `reverse`. False where fewer than three corners are left.
  bool close(const std::vector<int>& labels, bool reverse);

 private:
  Fragment& f_;
  std::vector<std::uint64_t> on_;
};

// The ordered list, first drawn first. For any two fragments whose projections
// overlap in an open set, the later one comes first in the order (depth, face
// index) wherever they overlap: nearer, or at equal depth of a lower face index.
// Counts (faces_considered, pair_tests, reorders, splits_by_plane, splits_by_cut,
// fragments_written) go to `stats`.
std::vector<Fragment> depth_sort(const ScreenScene& ss, Stats& stats);

}  // namespace vismap::engine
