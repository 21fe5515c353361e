#include "engine/culling.h"


#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/union_find.h"
#include "engine/world_exact.h"

namespace vismap::engine {
namespace {

}  // namespace

std::vector<std::int8_t> closed_component_sides(
    const Scene& scene, const WorldFacets& wf, const std::vector<WorldPiece>& pieces,
    const View& view, const std::function<bool(std::uint32_t)>& vertex_in_front) {
  const int n = static_cast<int>(wf.facets.size());
  UnionFind uf(static_cast<std::size_t>(n));
  // A piece closes the surface when exactly two facets share it, traversing it in
  // opposite directions (consistent orientation).
  std::vector<char> good(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto& s = pieces[i].sharers;
    good[i] = s.size() == 2 && s[0].forward != s[1].forward;
    for (std::size_t k = 1; k < s.size(); ++k) uf.join(s[0].facet, s[k].facet);
  }
  std::vector<char> closed(n, 1);
  for (std::size_t i = 0; i < pieces.size(); ++i)
    if (!good[i]) for (const auto& s : pieces[i].sharers) closed[uf.find(s.facet)] = 0;
  // A non-planar polygon's fan can fold over the polygon's own edge, and a face
  // never hides its own edges (spec: "some face g not sharing e"): an edge between
  // two back-facing pieces may then be visible. Such components are not culled.
  for (int f = 0; f < n; ++f)
    if (!wf.facets[f].planar) closed[uf.find(f)] = 0;

  // Eye outside: orthographic eyes are at infinity; a perspective eye must lie
  // strictly outside the component's bounding box, and the near plane must not cut it.
  std::vector<Vec3> lo(n, Vec3{HUGE_VAL, HUGE_VAL, HUGE_VAL}), hi(n, Vec3{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL});
  std::vector<Vec3> origin(n);
  std::vector<char> has_origin(n, 0);
  for (int f = 0; f < n; ++f) {
    int c = uf.find(f);
    if (!closed[c]) continue;
    for (auto id : wf.facets[f].v) {
      const Vec3& p = scene.vertices[id];
      if (view.perspective && !vertex_in_front(id)) closed[c] = 0;
      lo[c] = {std::min(lo[c].x, p.x), std::min(lo[c].y, p.y), std::min(lo[c].z, p.z)};
      hi[c] = {std::max(hi[c].x, p.x), std::max(hi[c].y, p.y), std::max(hi[c].z, p.z)};
      if (!has_origin[c]) { origin[c] = p; has_origin[c] = 1; }
    }
  }
  if (view.perspective)
    for (int c = 0; c < n; ++c) {
      if (!closed[c] || uf.find(c) != c) continue;
      const Vec3& e = view.eye;
      bool inside_box = e.x >= lo[c].x && e.x <= hi[c].x && e.y >= lo[c].y && e.y <= hi[c].y &&
                        e.z >= lo[c].z && e.z <= hi[c].z;
      if (inside_box) closed[c] = 0;
    }

  // Orientation of each closed component: the sign of its signed volume, a sum
  // of tetrahedra from one of its corners. Intervals settle it unless the
  // volume is (nearly) zero; then it is summed exactly.
  using Interval = CGAL::Interval_nt<false>;
  std::vector<Interval> volume(n, Interval(0));
  {
    CGAL::Protect_FPU_rounding<true> upward;
    for (int f = 0; f < n; ++f) {
      const int c = uf.find(f);
      if (!closed[c]) continue;
      const auto& v = wf.facets[f].v;
      for (std::size_t k = 1; k + 1 < v.size(); ++k)
        volume[c] += world::det<Interval>(origin[c], scene.vertices[v[0]], scene.vertices[v[k]], scene.vertices[v[k + 1]]);
    }
  }
  std::vector<std::int8_t> sign(n, 0);
  std::vector<CGAL::Mpzf> exact;
  for (int c = 0; c < n; ++c) {
    if (!closed[c] || uf.find(c) != c) continue;
    // Beyond 2^300 a product of three differences may overflow, and an interval
    // with an infinite bound is not to be trusted (inf * 0 is NaN, which a max
    // can drop): such a component is summed exactly.
    const double far = std::max({-lo[c].x, -lo[c].y, -lo[c].z, hi[c].x, hi[c].y, hi[c].z});
    if (!(far <= 0x1p300)) volume[c] = Interval(-1, 1);
    if (volume[c].inf() > 0) sign[c] = 1;
    else if (volume[c].sup() < 0) sign[c] = -1;
    else if (exact.empty()) exact.resize(n);   // (then summed below)
  }
  if (!exact.empty()) {
    for (int f = 0; f < n; ++f) {
      const int c = uf.find(f);
      if (!closed[c] || sign[c] != 0) continue;
      const auto& v = wf.facets[f].v;
      for (std::size_t k = 1; k + 1 < v.size(); ++k)
        exact[c] = exact[c] + world::det<CGAL::Mpzf>(origin[c], scene.vertices[v[0]], scene.vertices[v[k]], scene.vertices[v[k + 1]]);
    }
    for (int c = 0; c < n; ++c)
      if (closed[c] && uf.find(c) == c && sign[c] == 0) sign[c] = static_cast<std::int8_t>(exact[c].sign());
  }
  std::vector<std::int8_t> side(n, 0);
  for (int f = 0; f < n; ++f) {
    int c = uf.find(f);
    if (closed[c]) side[f] = sign[c];
  }
  return side;
}

}  // namespace vismap::engine
