#include "engine/self_contact.h"

#include <CGAL/Bbox_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "engine/world_exact.h"

namespace vismap::engine {

namespace {

using K = CGAL::Epick;   // (predicates only: exact)
using Point = K::Point_3;

struct Triangle {
  std::array<std::uint32_t, 3> v;   // canonical vertex ids
  std::array<const Vec3*, 3> corner;
  int facet;
};

// The fans of the facets, without the triangles whose corners are collinear
// (those lie on their facet's border, which its other triangles hold).
std::vector<Triangle> fans(const Scene& scene, const WorldFacets& wf, const std::vector<int>& facets) {
  std::vector<Triangle> out;
  for (int fi : facets) {
    const auto& v = wf.facets[static_cast<std::size_t>(fi)].v;
    for (std::size_t k = 1; k + 1 < v.size(); ++k)
      if (!world::collinear(scene.vertices[v[0]], scene.vertices[v[k]], scene.vertices[v[k + 1]]))
        out.push_back({{v[0], v[k], v[k + 1]},
                       {&scene.vertices[v[0]], &scene.vertices[v[k]], &scene.vertices[v[k + 1]]},
                       fi});
  }
  return out;
}

// Whether every point of a lies strictly on one side of b's plane (but the
// corners they share, which lie in it): then they meet at most there.
bool off_plane(const Triangle& a, const Triangle& b, const world::PlaneSide& plane_b) {
  int side = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto id = a.v[k];
    if (id == b.v[0] || id == b.v[1] || id == b.v[2]) continue;
    const int s = plane_b(*a.corner[k]);
    if (s == 0 || (side != 0 && s != side)) return false;
    side = s;
  }
  return true;
}

// Whether triangles a and b, of different facets, meet other than at the
// corners they share and along the edge between two shared corners.
bool meet(const Triangle& a, const Triangle& b, const world::PlaneSide& plane_a, const world::PlaneSide& plane_b) {
  auto P = [](const Vec3* p) { return Point(p->x, p->y, p->z); };
  // a's corners shared with b, and where they are in b.
  int shared = 0, ka[3], kb[3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a.v[i] == b.v[j]) {
        ka[shared] = i;
        kb[shared] = j;
        ++shared;
      }
  if (shared == 3) return true;   // (the same triangle twice)
  if (shared == 2) {
    // Along the shared edge p q: they meet beyond it only folded onto each other,
    // in one plane, on one side.
    const Vec3* s = b.corner[static_cast<std::size_t>(3 - kb[0] - kb[1])];
    if (plane_a(*s) != 0) return false;
    const auto k = static_cast<std::size_t>(3 - ka[0] - ka[1]);
    return CGAL::coplanar_orientation(P(a.corner[ka[0]]), P(a.corner[ka[1]]), P(a.corner[k]), P(s)) == CGAL::POSITIVE;
  }
  if (off_plane(a, b, plane_b) || off_plane(b, a, plane_a)) return false;
  const K::Triangle_3 ta(P(a.corner[0]), P(a.corner[1]), P(a.corner[2]));
  const K::Triangle_3 tb(P(b.corner[0]), P(b.corner[1]), P(b.corner[2]));
  if (shared == 0) return CGAL::do_intersect(ta, tb);
  // One shared corner: they meet elsewhere only where the edge of one opposite
  // it meets the other.
  const K::Segment_3 ea(P(a.corner[(ka[0] + 1) % 3]), P(a.corner[(ka[0] + 2) % 3]));
  const K::Segment_3 eb(P(b.corner[(kb[0] + 1) % 3]), P(b.corner[(kb[0] + 2) % 3]));
  return CGAL::do_intersect(ea, tb) || CGAL::do_intersect(eb, ta);
}

// Pairs of boxes that meet (closed boxes), each once, until `f` returns true: a
// uniform grid of about one cell per box, each box listed in the cells it
// meets; a pair is taken in the cell of the lower corner of its common box.
template <class F>
bool any_box_pair(const std::vector<CGAL::Bbox_3>& boxes, F&& f) {
  const std::size_t n = boxes.size();
  if (n < 2) return false;
  CGAL::Bbox_3 all = boxes[0];
  double size = 0;
  for (const auto& b : boxes) {
    all += b;
    size += std::max({b.xmax() - b.xmin(), b.ymax() - b.ymin(), b.zmax() - b.zmin()});
  }
  const std::array<double, 3> lo{all.xmin(), all.ymin(), all.zmin()};
  const std::array<double, 3> extent{all.xmax() - all.xmin(), all.ymax() - all.ymin(), all.zmax() - all.zmin()};
  // Cells about a box's size, at most 4 per box (1 where the extent is not finite).
  double h = size / static_cast<double>(n);
  std::array<int, 3> g{1, 1, 1};
  const double most = 4.0 * static_cast<double>(n) + 64;
  for (int tries = 0; tries < 200 && std::isfinite(extent[0] + extent[1] + extent[2]); ++tries, h *= 1.25) {
    if (!(h > 0)) break;
    std::array<double, 3> c{};
    for (int k = 0; k < 3; ++k) c[k] = std::max(1.0, std::ceil(extent[k] / h));
    if (c[0] * c[1] * c[2] <= most) {
      for (int k = 0; k < 3; ++k) g[k] = static_cast<int>(c[k]);
      break;
    }
  }
  auto cell = [&](int k, double x) {
    const double t = g[k] > 1 ? std::floor((x - lo[k]) / h) : 0;
    if (!(t >= 0)) return 0;
    return t < g[k] ? static_cast<int>(t) : g[k] - 1;
  };
  auto index = [&](int x, int y, int z) { return (static_cast<std::size_t>(z) * g[1] + y) * g[0] + x; };
  auto for_cells = [&](const CGAL::Bbox_3& b, auto&& visit) {
    const int x0 = cell(0, b.xmin()), x1 = cell(0, b.xmax()), y0 = cell(1, b.ymin()), y1 = cell(1, b.ymax());
    const int z0 = cell(2, b.zmin()), z1 = cell(2, b.zmax());
    for (int z = z0; z <= z1; ++z)
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) visit(index(x, y, z));
  };
  const std::size_t cells = static_cast<std::size_t>(g[0]) * g[1] * g[2];
  std::vector<std::uint32_t> start(cells + 1, 0);
  for (const auto& b : boxes) for_cells(b, [&](std::size_t c) { ++start[c + 1]; });
  for (std::size_t c = 1; c <= cells; ++c) start[c] += start[c - 1];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1), member(start.back());
  for (std::size_t i = 0; i < n; ++i) for_cells(boxes[i], [&](std::size_t c) { member[fill[c]++] = static_cast<std::uint32_t>(i); });
  // Each box's lowest cell (the cell of a common box's lower corner is the
  // largest of the two boxes' in each axis: cell() is monotone).
  std::vector<std::array<int, 3>> low(n);
  for (std::size_t i = 0; i < n; ++i) low[i] = {cell(0, boxes[i].xmin()), cell(1, boxes[i].ymin()), cell(2, boxes[i].zmin())};
  // In each cell, its boxes by their lower x: a box meets only those after it
  // that start before it ends.
  for (std::size_t c = 0; c < cells; ++c) {
    const auto first = member.begin() + start[c], last = member.begin() + start[c + 1];
    std::sort(first, last, [&](std::uint32_t i, std::uint32_t j) { return boxes[i].xmin() < boxes[j].xmin(); });
    for (auto s = first; s != last; ++s) {
      const CGAL::Bbox_3& a = boxes[*s];
      for (auto t = s + 1; t != last && boxes[*t].xmin() <= a.xmax(); ++t) {
        const CGAL::Bbox_3& b = boxes[*t];
        if (a.ymax() < b.ymin() || b.ymax() < a.ymin() || a.zmax() < b.zmin() || b.zmax() < a.zmin()) continue;
        const auto &la = low[*s], &lb = low[*t];
        const std::size_t home = index(std::max(la[0], lb[0]), std::max(la[1], lb[1]), std::max(la[2], lb[2]));
        if (home == c && f(*s, *t)) return true;
      }
    }
  }
  return false;
}

}  // namespace

bool meets_itself(const Scene& scene, const WorldFacets& wf, const std::vector<int>& facets) {
  const std::vector<Triangle> tris = fans(scene, wf, facets);
  std::vector<CGAL::Bbox_3> boxes;
  std::vector<world::PlaneSide> planes;   // (each triangle's normal once, for the side tests)
  boxes.reserve(tris.size());
  planes.reserve(tris.size());
  for (const Triangle& t : tris) {
    CGAL::Bbox_3 b;
    for (const Vec3* p : t.corner) b += CGAL::Bbox_3(p->x, p->y, p->z, p->x, p->y, p->z);
    boxes.push_back(b);
    planes.emplace_back(*t.corner[0], *t.corner[1], *t.corner[2]);
  }
  return any_box_pair(boxes, [&](std::uint32_t i, std::uint32_t j) {
    return tris[i].facet != tris[j].facet && meet(tris[i], tris[j], planes[i], planes[j]);
  });
}

}  // namespace vismap::engine
