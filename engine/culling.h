// Stage 3: which facets can be skipped because they face away inside a closed,
// consistently oriented component seen from outside. Decided exactly; when in
// doubt (open surface, eye near or inside, cut by the near plane) nothing is culled.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "engine/camera.h"
#include "engine/edge_pieces.h"

namespace vismap::engine {

// Per facet: +1 = part of an outward-oriented closed component (its back-facing
// facets are hidden), -1 = inward-oriented (its front-facing facets are hidden),
// 0 = nothing can be said.
std::vector<std::int8_t> closed_component_sides(
    const Scene& scene, const WorldFacets& wf, const std::vector<WorldPiece>& pieces,
    const View& view, const std::function<bool(std::uint32_t)>& vertex_in_front);

}  // namespace vismap::engine
