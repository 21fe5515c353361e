// Vertex stars that lie flat on the screen. Internal to the engine (CGAL types).
//
// On a mesh, most pairs of facets a piercing search meets are neighbours that
// share one corner v (the pairs that share an edge are told apart by it). Where
// the facets around v are triangles that turn the same way on the screen and
// go round v exactly once, their projections tile a disk around v, each
// triangle within its own angle at v: two of them meet only on a common edge
// or at v, and a crossing strictly inside both projections cannot exist. So one
// test per vertex answers all its pairs, with no arithmetic per pair.
#pragma once
#include <vector>

#include "engine/screen_scene.h"

namespace vismap::engine {
VISMAP_KERNEL_BEGIN

class EmbeddedStars {
 public:
  // The stars of the occluding facets' corners, on `threads` threads; none
  // (every star taken as not embedded) unless `wanted`.
  EmbeddedStars(const ScreenScene& ss, int threads, bool wanted = true);
  // Whether the star of canonical vertex v (not -1) is embedded: then two of
  // its facets that have no other corner in common do not pierce each other.
  bool at(VertexId v) const { return embedded_[static_cast<std::size_t>(v)] != 0; }
  // How many vertices have an embedded star (for --stats).
  long count() const;

 private:
  std::vector<char> embedded_;   // per canonical vertex id
};

VISMAP_KERNEL_END
}  // namespace vismap::engine
