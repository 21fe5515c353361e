#include "engine/holed_faces.h"

#include <CGAL/Constrained_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <deque>
#include <string>

#include "engine/input_polygon.h"

namespace vismap::engine {
namespace {

// Inputs are doubles and nothing is constructed: Epick's predicates are exact.
using K = CGAL::Epick;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;   // canonical vertex id
using Fb = CGAL::Triangulation_face_base_with_info_2<int, K, CGAL::Constrained_triangulation_face_base_2<K>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Constraints that cross, overlap or meet inside an edge are refused by the
// triangulation itself (Intersection_of_constraints_exception).
using CT = CGAL::Constrained_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;

[[noreturn]] void refuse(const Scene& scene, std::size_t f, const std::string& what) {
  throw InputError(scene.file + ": face " + std::to_string(f) + " " + what);
}

// One ring: canonical ids and points, consecutive repeats (cyclically) dropped.
struct Ring {
  std::vector<std::uint32_t> ids;
  std::vector<Q3> p;
};

Ring ring_of(const Scene& scene, const std::vector<std::uint32_t>& canon, const IndexRing& r) {
  Ring out;
  distinct_corners(scene, canon, r, out.ids, out.p);
  return out;
}

// How a simple ring turns in the plane: as it does at its lexicographically
// smallest corner (a convex corner, where the turn is never straight).
CGAL::Orientation turn(const Ring& r, int axis) {
  std::vector<Q2> q;
  for (const Q3& p : r.p) q.push_back(drop_axis(p, axis));
  const std::size_t n = q.size();
  const std::size_t m = static_cast<std::size_t>(std::min_element(q.begin(), q.end()) - q.begin());
  return CGAL::orientation(q[(m + n - 1) % n], q[m], q[(m + 1) % n]);
}

// Nesting depth of every face: 0 outside, +1 across each constrained edge
// (CGAL's polygon-with-holes recipe): the face's inside is depth 1.
void mark_depths(CT& ct) {
  for (auto fh = ct.all_faces_begin(); fh != ct.all_faces_end(); ++fh) fh->info() = -1;
  std::deque<CT::Edge> border;
  auto flood = [&](CT::Face_handle start, int depth) {
    if (start->info() != -1) return;
    std::deque<CT::Face_handle> queue{start};
    while (!queue.empty()) {
      CT::Face_handle fh = queue.front();
      queue.pop_front();
      if (fh->info() != -1) continue;
      fh->info() = depth;
      for (int i = 0; i < 3; ++i) {
        CT::Face_handle n = fh->neighbor(i);
        if (n->info() != -1) continue;
        if (ct.is_constrained(CT::Edge(fh, i))) border.push_back(CT::Edge(fh, i));
        else queue.push_back(n);
      }
    }
  };
  flood(ct.infinite_face(), 0);
  while (!border.empty()) {
    const CT::Edge e = border.front();
    border.pop_front();
    CT::Face_handle n = e.first->neighbor(e.second);
    if (n->info() == -1) flood(n, e.first->info() + 1);
  }
}

// The depths on the two sides of the ring's edges: {0, 1} for the outer ring,
// {1, 2} for a hole; false when an edge is not one of the triangulation's (a
// vertex of another ring lies on it) or a side has another depth.
bool separates(const CT& ct, const std::vector<CT::Vertex_handle>& v, int inner) {
  for (std::size_t k = 0; k < v.size(); ++k) {
    CT::Face_handle fh;
    int i;
    if (!ct.is_edge(v[k], v[(k + 1) % v.size()], fh, i)) return false;
    const int a = fh->info(), b = fh->neighbor(i)->info();
    if (std::min(a, b) != inner - 1 || std::max(a, b) != inner) return false;
  }
  return true;
}

}  // namespace

void facets_of_holed_face(const Scene& scene, const std::vector<std::uint32_t>& canon, std::size_t f,
                          WorldFacets& out) {
  std::vector<Ring> rings{ring_of(scene, canon, scene.faces[f])};
  std::size_t i1, i2;
  if (!find_plane(rings[0].p, i1, i2)) {
    ++out.degenerate;   // the outer ring has no area: dropped, as any degenerate polygon
    return;
  }
  const Q3 a = rings[0].p[0], b = rings[0].p[i1], c = rings[0].p[i2];
  const std::vector<IndexRing>& holes = scene.holes_of(f);
  for (std::size_t h = 0; h < holes.size(); ++h) {
    rings.push_back(ring_of(scene, canon, holes[h]));
    std::size_t j1, j2;
    if (!find_plane(rings.back().p, j1, j2)) refuse(scene, f, "has hole " + std::to_string(h) + " with no area");
  }
  for (const Ring& r : rings)
    for (const Q3& p : r.p)
      if (CGAL::orientation(a, b, c, p) != CGAL::COPLANAR)
        refuse(scene, f, "has holes, so it must be planar, but its corners do not lie in one plane");

  const int axis = dominant_axis(a, b, c);
  CT ct;
  std::vector<std::vector<CT::Vertex_handle>> handles(rings.size());
  for (std::size_t k = 0; k < rings.size(); ++k) {
    std::vector<Q2> q;
    for (const Q3& p : rings[k].p) q.push_back(drop_axis(p, axis));
    if (!is_simple_ring(q))
      refuse(scene, f, k == 0 ? "has an outer ring that crosses or touches itself"
                              : "has hole " + std::to_string(k - 1) + ", which crosses or touches itself");
    for (std::size_t i = 0; i < q.size(); ++i) {
      handles[k].push_back(ct.insert(q[i]));
      handles[k].back()->info() = rings[k].ids[i];
    }
  }
  try {
    for (const auto& v : handles)
      for (std::size_t i = 0; i < v.size(); ++i) ct.insert_constraint(v[i], v[(i + 1) % v.size()]);
  } catch (const CT::Intersection_of_constraints_exception&) {
    refuse(scene, f, "has rings that cross or overlap each other");
  }
  mark_depths(ct);
  if (!separates(ct, handles[0], 1)) refuse(scene, f, "has a hole that crosses or touches its outer ring's edges");
  for (std::size_t k = 1; k < handles.size(); ++k)
    if (!separates(ct, handles[k], 2))
      refuse(scene, f, "has hole " + std::to_string(k - 1) +
                           ", which is not inside the outer ring and outside the other holes (or touches an edge)");

  // The triangles inside, turned as the outer ring is (its turn says which side is the front).
  const bool reverse = turn(rings[0], axis) == CGAL::RIGHT_TURN;
  const int face = static_cast<int>(f);
  ++out.nonconvex;
  for (auto fh = ct.finite_faces_begin(); fh != ct.finite_faces_end(); ++fh) {
    if (fh->info() != 1) continue;
    int order[3] = {0, 1, 2};
    if (reverse) std::swap(order[1], order[2]);
    WorldFacet t{face, true, true, {}, {}};
    for (int k = 0; k < 3; ++k) {
      const int i = order[k], j = order[(k + 1) % 3];
      t.v.push_back(fh->vertex(i)->info());
      // The edge from vertex i to j is the one opposite the third vertex.
      t.role.push_back(fh->is_constrained(3 - i - j) ? EdgeRole::Boundary : EdgeRole::Internal);
    }
    out.facets.push_back(std::move(t));
  }
}

}  // namespace vismap::engine
