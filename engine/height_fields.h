// Open surfaces that are the graph of a function over a coordinate plane (a
// terrain over its ground, a relief, a sheet that never turns back on itself):
// they meet themselves nowhere, so the search for faces that pierce each
// other can pass over every pair of their facets. World space, exact, no
// camera: decided once per scene. Internal to the engine.
#pragma once
#include <vector>

#include "engine/edge_pieces.h"
#include "engine/scene.h"
#include "engine/world_facets.h"

namespace vismap::engine {

// Per facet: component[facet] where its component (ClosedComponents::connected_components():
// facets joined by the pieces they share) is certified to meet itself nowhere
// (two of its facets meet only at the corners and along the edge they share),
// else -1. Certified: a component of triangles that is a topological disk (each
// piece shared by at most two of them, in opposite directions; every vertex's
// triangles one fan; V - E + F = 1; one boundary loop) and that, seen along one
// coordinate axis, turns positively in every triangle, goes round each inner
// vertex once and less than once round each boundary vertex (a local one to one
// map), with a boundary loop that does not cross itself. A local homeomorphism
// of a disk into the plane that is one to one on the boundary circle is one to
// one: the projection is, and so two facets meet only where it says. Exact
// (orientations and comparisons of input doubles). On `threads` threads.
std::vector<int> height_field_components(const Scene& scene, const WorldFacets& wf,
                                         const std::vector<WorldPiece>& pieces, const std::vector<int>& component,
                                         int threads = 1);

}  // namespace vismap::engine
