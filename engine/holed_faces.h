// Stage 1 for faces with holes: a planar polygon with hole rings -> triangles
// in world space, by a constrained triangulation of its image in a coordinate
// plane. The rings' edges are the facets' boundary edges; every other edge is
// internal (never drawn). Any triangulation of a planar face covers the same
// set, so the map does not depend on which one this is.
#pragma once
#include <cstdint>
#include <vector>

#include "engine/world_facets.h"

namespace vismap::engine {

// Appends face f's triangles to `out` (counted as non-convex), or counts it as
// degenerate when its outer ring has no area. Throws InputError, naming the
// scene's file and the face, when the face is not planar, a hole has no area,
// a ring crosses or touches itself or another ring's edge, or a hole is not
// inside the outer ring and outside the other holes. `canon`: canonical
// vertex ids (make_world_facets).
void facets_of_holed_face(const Scene& scene, const std::vector<std::uint32_t>& canon, std::size_t f,
                          WorldFacets& out);

}  // namespace vismap::engine
