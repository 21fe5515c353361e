// Stage 3: which facets can be skipped because they face away inside a closed,
// consistently oriented shell that does not meet itself. Decided exactly;
// when in doubt (open surface, a non-planar fan, a surface crossing or touching
// itself) nothing is culled.
//
// A ray from the eye starts at the near plane (what lies before it is clipped).
// If it starts outside a closed solid, the first face of the solid it meets is
// entered, so faces seen from behind are hidden by the solid's own front faces.
// Only rays that start inside the solid (in a cap: where the near plane cuts
// it) see faces from behind. So a back face is culled unless its screen image
// may meet the image of one of its component's caps; the eye's place does not
// matter (inside the solid, its cap is simply large).
#pragma once
#include <CGAL/Bbox_2.h>

#include <cstdint>
#include <functional>
#include <vector>

#include "engine/camera.h"
#include "engine/edge_pieces.h"

namespace vismap::engine {

struct ClosedComponents {
  // Per facet: its shell (a facet index): facets joined across the pieces that
  // exactly two facets share, and across those more share between facets whose
  // edges join the same two input vertices. Solids that touch along an edge or
  // a face are shells apart, each closed or not on its own.
  std::vector<int> component;
  // Per facet: its connected component (a facet index), facets joined across
  // every piece they share, where some piece has more than two sharers; else
  // empty: the shells are the components.
  std::vector<int> connected;
  const std::vector<int>& connected_components() const { return connected.empty() ? component : connected; }
  // Per facet: +1 = part of an outward-oriented closed component that does not
  // meet itself (its back-facing facets are hidden), -1 = inward-oriented (its
  // front-facing facets are hidden), 0 = nothing can be said.
  std::vector<std::int8_t> side;
};
ClosedComponents closed_components(const Scene& scene, const WorldFacets& wf, const std::vector<WorldPiece>& pieces,
                                   int threads = 1);

// A box containing the screen image of one connected curve of the near plane's
// cut through a closed component, and so of the caps it bounds.
struct NearCap {
  int component;
  CGAL::Bbox_2 box;
};

// What the near plane cut of a perspective view tells about the world (from the
// projection step): the exact sign of an input vertex's Z (the near plane is
// Z = 0), the box of a facet's near-plane cut (false: not cut), and the box of a
// vertex lying on the near plane.
struct NearPlane {
  std::function<int(std::uint32_t)> z_sign;
  std::function<bool(int, CGAL::Bbox_2&)> facet_cut;
  std::function<CGAL::Bbox_2(std::uint32_t)> on_plane;
};

// The caps of the closed components the near plane cuts (perspective only).
std::vector<NearCap> near_caps(const WorldFacets& wf, const std::vector<WorldPiece>& pieces,
                               const ClosedComponents& cc, const NearPlane& np);

// Per facet: hidden if it faces away from the eye in its closed component (its
// side), because its screen box is apart from every cap of its component. On
// `threads` threads.
std::vector<char> hidden_when_back_facing(const ClosedComponents& cc, const std::vector<NearCap>& caps,
                                          const std::vector<CGAL::Bbox_2>& facet_box, int threads = 1);

}  // namespace vismap::engine
