// The BSP tree (lecture notes on hidden-surface removal, "binary space
// partitioning"): built once per scene in world space, with exact splitting
// planes; traversed per view, it gives a drawing order (back to front) from any
// eye. Fragments keep their facet (and so their face); split points are exact
// rationals. Camera-independent, so several views of one scene share it.
// Internal to the engine (no CGAL type).
#pragma once
#include <gmpxx.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/camera.h"
#include "engine/scene.h"
#include "engine/world_facets.h"

namespace vismap::engine {

struct BspTree {
  // A fragment's corner: an input vertex (its canonical id), or a point where a
  // splitting plane cut a fragment's edge a -> b: a + t (b - a), exactly.
  struct Point {
    std::int64_t vertex = -1;
    std::uint32_t a = 0, b = 0;   // (split points only: indices in `points`)
    mpq_class t;                  //   (a parallel projection keeps t on the screen)
    mpq_class x, y, z;            //   its world coordinates
  };
  // A convex piece of a world facet, its corners in the facet's order.
  struct Fragment {
    std::uint32_t facet = 0;   // index in `facets` (make_world_facets' order)
    std::vector<std::uint32_t> corners;   // indices in `points`
    std::vector<int> edge;   // per edge corners[k] -> corners[k+1]: the edge of its world facet
                             // (v[j] -> v[j+1]) whose line holds it, or -1 (a splitting plane's)
  };
  // A node's plane is its first fragment's facet's, spanned by three of its
  // corners (input vertices); `on` lists the fragments in that plane.
  struct Node {
    std::uint32_t span[3] = {0, 0, 0};   // input vertex ids
    std::vector<std::uint32_t> on;
    int front = -1, back = -1;           // subtrees: the plane's positive and negative sides
  };

  std::shared_ptr<const WorldFacets> facets;   // the scene's facets, as every engine makes them
  std::vector<Point> points;
  std::vector<Fragment> fragments;
  std::vector<Node> nodes;
  int root = -1;
  exact::FilterCounts counted;   // the filtered predicates its making ran (a view that finds it
                                 // made counts them, as a view that makes it does)
  std::int64_t splits = 0;   // fragments cut in two
  int depth = 0;             // the longest path from the root, in nodes
};

// The tree of the scene's facets (all of them: culling depends on the view).
// Throws InputError as make_world_facets does.
BspTree build_bsp_tree(const Scene& scene, int threads = 1);

// The tree of some of the facets `wf` holds (indices in wf->facets).
BspTree build_bsp_tree(const Scene& scene, std::shared_ptr<const WorldFacets> wf,
                       const std::vector<std::uint32_t>& facets);

// The fragments in drawing order for a view's eye (eye_of, below; first drawn
// first), a point (perspective) or at infinity against the view direction:
// for any two whose projections overlap in an open set, the later one is nearer
// there, or at equal depth of a lower face index. Fragments in planes seen
// edge-on come in any place (they hide nothing).
struct Eye;
std::vector<std::uint32_t> back_to_front(const BspTree& tree, const Scene& scene, const Eye& eye);

// The eye as the view's projection sees it, exactly, in homogeneous coordinates
// (x, y, z, w), w >= 0: the centre of projection (where the rows X, Y and W of
// the view vanish: the doubles of view.eye are only near it), w > 0; or,
// orthographically, the point at infinity (w = 0) towards which the screen
// projects (against r x u, r and u the rows X and Y: the direction that keeps a
// screen point). A plane is seen edge-on exactly when this point lies in it.
struct Eye {
  std::array<mpq_class, 4> h;
  std::array<std::array<double, 2>, 4> near;   // intervals around h
};
Eye eye_of(const View& view);

// The side of the plane through input vertex p with normal (q - p) x (s - r)
// (a facet's plane: r = p) that the eye is on: +1, -1, or 0 in it. Exact.
int eye_side(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, const Eye& eye);

}  // namespace vismap::engine
