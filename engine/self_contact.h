// Whether a closed component meets itself: two of its facets touching or
// crossing anywhere but along the corners and edges they share. Only a
// component that does not (an embedded surface: every point off it is inside
// once or not at all) bounds a solid whose inside and outside can be told by
// parity; a mesh whose parts overlap (a leg through the body) has places inside
// twice. World space, exact. Internal to the engine.
#pragma once
#include <vector>

#include "engine/scene.h"
#include "engine/world_facets.h"

namespace vismap::engine {

// Whether any two of `facets` (indices into wf, planar convex facets of one
// component) meet other than at the corners they share (by canonical vertex id)
// and along the edges between those. Facets with collinear corners are taken as
// their fans' non-degenerate triangles.
// On `threads` threads.
bool meets_itself(const Scene& scene, const WorldFacets& wf, const std::vector<int>& facets, int threads = 1);
// The same for each of several components, in one pass (per component: 1 if it meets itself).
std::vector<char> meets_itself(const Scene& scene, const WorldFacets& wf, const std::vector<std::vector<int>>& components,
                               int threads = 1);

}  // namespace vismap::engine
