// Stage 1: input polygons -> convex planar facets in world space.
// Degenerate polygons are dropped (counted); non-convex planar polygons are
// triangulated by ear clipping, non-planar ones by a fan from the first vertex,
// polygons with holes by a constrained triangulation (engine/holed_faces.h).
// Every facet keeps its polygon's index; diagonals are marked internal.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "engine/scene.h"
#include "engine/small_vec.h"
#include "engine/world_exact.h"

namespace vismap::engine {

enum class EdgeRole : std::uint8_t {
  Boundary,   // an edge of the input polygon: may be drawn
  Internal,   // a diagonal inside one polygon: never drawn
  Clip        // the near-plane cut of a perspective view: never drawn
};

// (48 bytes, a triangle's or a quad's corners inline: a million facets are common.)
struct WorldFacet {
  int face = -1;                        // input face index
  bool planar = true;                   // false: a fan piece of a non-planar polygon
  // A triangle of a simple planar polygon's triangulation (ear clipping, or a
  // face with holes), not a fan's: across each of its diagonals the polygon goes
  // on, in its plane, on the other side.
  bool split = false;
  SmallVec<std::uint32_t, 4> v;         // input vertex ids, in the polygon's order
  SmallVec<EdgeRole, 8> role;           // role[i]: edge v[i] -> v[i+1]
};

struct WorldFacets {
  std::vector<WorldFacet> facets;
  // Per facet, its unit normal estimated from its spanning corners (a
  // triangle's; unknown for a larger polygon), for crease tests: kept in the
  // facets' order wherever they are reordered (empty: none known).
  std::vector<world::UnitNormal> normals;
  std::int64_t degenerate = 0, nonplanar = 0, nonconvex = 0;
};

// Three corners of a facet that span its plane (input vertex ids): the first
// corner and the first two consecutive ones after it that are not collinear
// with it (a triangle's own three). Exact.
std::array<std::uint32_t, 3> spanning_ids(const Scene& scene, const WorldFacet& w);

// Vertex ids in facets are canonical: equal coordinates give one id, so that
// polygon soups share end points by identity. Chunks of faces on `threads` threads.
// Throws InputError for a face with holes that is not what Scene allows.
WorldFacets make_world_facets(const Scene& scene, int threads = 1);

// The vertices the facets use, in the order they first use them: used[k] is
// the k-th one's input id, local[id] its place in used (~0u where unused), for
// each of nvertices input vertices. (Where facets lie in screen order, what is
// stored at these places is read nearly in sequence.)
void number_by_first_use(const WorldFacets& wf, std::size_t nvertices, std::vector<std::uint32_t>& used,
                         std::vector<std::uint32_t>& local);

}  // namespace vismap::engine
