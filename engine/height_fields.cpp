#include "engine/height_fields.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>

#include "engine/parallel.h"
#include "engine/star_link.h"
#include "engine/world_exact.h"

namespace vismap::engine {
namespace {

using K = CGAL::Epick;   // (predicates only: exact on the input's doubles)
using Point = K::Point_2;

// A coordinate plane as a component is seen in: the two axes other than the
// one looked along, in the order that makes its triangles turn positively.
struct Plane {
  int u = 0, w = 1;
  Point at(const Vec3& p) const { return Point(coordinate(p, u), coordinate(p, w)); }
};

// Looking along the largest component of a surface's summed normals (any axis
// gives an exact answer; this one lets a surface that faces mostly that way
// pass), the axes in the order that makes its triangles turn positively.
Plane plane_of(const std::array<double, 3>& n) {
  int k = 0;
  for (int j = 1; j < 3; ++j)
    if (std::abs(n[static_cast<std::size_t>(j)]) > std::abs(n[static_cast<std::size_t>(k)])) k = j;
  Plane p{(k + 1) % 3, (k + 2) % 3};
  if (n[static_cast<std::size_t>(k)] < 0) std::swap(p.u, p.w);
  return p;
}

// What is counted per component.
struct Tally {
  std::int64_t facets = 0, vertices = 0, pieces = 0, border = 0, uses = 0;
  std::array<double, 3> normal{};   // the sum of its triangles' normals
  std::uint32_t border_vertex = 0;  // a vertex of its boundary
};

// Whether the triangles (v, from(i), to(i)), i < n, each turning positively in
// the plane, make one fan from one of v's boundary neighbours (`ends`) to the
// other that turns less than once round v: their link edges one path through all n, and no
// step of it sweeping over the direction it started from.
template <class From, class To>
bool boundary_fan(std::size_t n, From&& from, To&& to, const Point& v, const std::array<std::uint32_t, 2>& ends,
                  const std::vector<Vec3>& world, const Plane& plane) {
  if (n < 1 || n > kMaxStar) return false;
  std::size_t next[kMaxStar];
  bool has_previous[kMaxStar] = {};
  for (std::size_t i = 0; i < n; ++i) {
    next[i] = n;
    for (std::size_t j = 0; j < n; ++j)
      if (from(j) == to(i)) {
        if (next[i] != n || has_previous[j]) return false;
        next[i] = j;
        has_previous[j] = true;
      }
  }
  std::size_t start = n;
  for (std::size_t i = 0; i < n; ++i)
    if (!has_previous[i]) {
      if (start != n) return false;
      start = i;
    }
  if (start == n) return false;   // (a cycle)
  std::size_t path[kMaxStar];
  std::size_t at = start, steps = 0;
  for (; at != n && steps < n; at = next[at]) path[steps++] = at;
  if (at != n || steps != n) return false;
  const std::uint32_t first = from(path[0]), last = to(path[n - 1]);
  if (!((first == ends[0] && last == ends[1]) || (first == ends[1] && last == ends[0]))) return false;
  auto p = [&](std::size_t k) { return plane.at(world[k < n ? from(path[k]) : last]); };
  const Point p0 = p(0);
  for (std::size_t k = 1; k <= n; ++k) {
    const Point before = p(k - 1), here = p(k);
    if (CGAL::orientation(v, before, p0) == CGAL::LEFT_TURN && CGAL::orientation(v, p0, here) != CGAL::RIGHT_TURN)
      return false;
  }
  return true;
}

// Whether the closed polyline of `segments` (pairs of vertex ids, each vertex
// in two) crosses or touches itself in the plane: two segments meeting anywhere
// but at the end they share, and two neighbours folding back over each other.
// A uniform grid of about one cell per segment, each pair looked at in the
// cells both pass.
bool loop_is_simple(const std::vector<std::array<std::uint32_t, 2>>& segments, const std::vector<Vec3>& world,
                    const Plane& plane) {
  auto at = [&](std::uint32_t id) { return plane.at(world[id]); };
  auto apart = [&](const std::array<std::uint32_t, 2>& s, const std::array<std::uint32_t, 2>& t) {
    int shared = 0;
    std::uint32_t common = 0;
    for (auto a : s)
      for (auto b : t)
        if (a == b) {
          ++shared;
          common = a;
        }
    if (shared == 2) return false;
    if (shared == 1) {
      const std::uint32_t x = s[0] == common ? s[1] : s[0], y = t[0] == common ? t[1] : t[0];
      const Point c = at(common), px = at(x), py = at(y);
      return !(CGAL::orientation(c, px, py) == CGAL::COLLINEAR && CGAL::compare_xy(px, c) == CGAL::compare_xy(py, c));
    }
    return !CGAL::do_intersect(K::Segment_2(at(s[0]), at(s[1])), K::Segment_2(at(t[0]), at(t[1])));
  };
  const std::size_t n = segments.size();
  if (n <= 16) {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (!apart(segments[i], segments[j])) return false;
    return true;
  }
  CGAL::Bbox_2 box = at(segments[0][0]).bbox();
  for (const auto& s : segments) box += at(s[0]).bbox() + at(s[1]).bbox();
  const int side = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(n))));
  const double wx = (box.xmax() - box.xmin()) / side, wy = (box.ymax() - box.ymin()) / side;
  auto cell = [&](double x, double lo, double width) {
    return width > 0 ? std::clamp(static_cast<int>((x - lo) / width), 0, side - 1) : 0;
  };
  std::vector<std::vector<std::uint32_t>> cells(static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
  for (std::size_t i = 0; i < n; ++i) {
    // (A segment whose box reaches a cell only by rounding is listed there too: harmless.)
    const CGAL::Bbox_2 b = at(segments[i][0]).bbox() + at(segments[i][1]).bbox();
    for (int y = cell(b.ymin(), box.ymin(), wy); y <= cell(b.ymax(), box.ymin(), wy); ++y)
      for (int x = cell(b.xmin(), box.xmin(), wx); x <= cell(b.xmax(), box.xmin(), wx); ++x)
        cells[static_cast<std::size_t>(y) * static_cast<std::size_t>(side) + static_cast<std::size_t>(x)].push_back(
            static_cast<std::uint32_t>(i));
  }
  for (const auto& c : cells)
    for (std::size_t i = 0; i < c.size(); ++i)
      for (std::size_t j = i + 1; j < c.size(); ++j)
        if (!apart(segments[c[i]], segments[c[j]])) return false;
  return true;
}

}  // namespace

std::vector<int> height_field_components(const Scene& scene, const WorldFacets& wf,
                                         const std::vector<WorldPiece>& pieces, const std::vector<int>& component,
                                         int threads) {
  const std::size_t n = wf.facets.size(), nv = scene.vertices.size();
  std::vector<int> out(n, -1);
  // (A closed surface has no boundary: most meshes leave here.)
  if (component.size() != n ||
      std::none_of(pieces.begin(), pieces.end(), [](const WorldPiece& p) { return p.sharers.size() == 1; }))
    return out;
  const std::vector<Vec3>& world = scene.vertices;
  auto corners = [&](std::size_t f) -> const SmallVec<std::uint32_t, 4>& { return wf.facets[f].v; };
  // The components numbered 0, 1, ... in the order of their first facets.
  std::vector<std::uint32_t> number(n, ~0u), comp(n);
  std::size_t ncomp = 0;
  for (std::size_t f = 0; f < n; ++f) {
    std::uint32_t& k = number[static_cast<std::size_t>(component[f])];
    if (k == ~0u) k = static_cast<std::uint32_t>(ncomp++);
    comp[f] = k;
  }
  std::vector<std::uint32_t>().swap(number);

  // Combinatorics first: components of two triangles or more, their counts, the
  // vertices each uses (one used by two components fails both).
  std::vector<Tally> tally(ncomp);
  std::vector<char> ok(ncomp, 1);
  std::vector<int> owner(nv, -1);   // the component using a vertex (-2: several)
  const bool estimated = wf.normals.size() == n;
  for (std::size_t f = 0; f < n; ++f) {
    const std::uint32_t c = comp[f];
    Tally& t = tally[c];
    ++t.facets;
    const auto& v = corners(f);
    if (v.size() != 3) ok[c] = 0;
    else {
      // (Only the axis depends on it: the facets' unit normals where estimated,
      // read in sequence, not their corners, a cache miss each.)
      if (estimated) {
        for (std::size_t k = 0; k < 3; ++k) t.normal[k] += wf.normals[f].n[k];
      } else {
        const auto nf = world::normal_of<double>(world[v[0]], world[v[1]], world[v[2]]);
        for (std::size_t k = 0; k < 3; ++k) t.normal[k] += nf[k];
      }
    }
    for (const std::uint32_t id : corners(f)) {
      if (owner[id] == -1) {
        owner[id] = static_cast<int>(c);
        ++t.vertices;
      } else if (owner[id] != static_cast<int>(c)) {
        if (owner[id] >= 0) ok[static_cast<std::size_t>(owner[id])] = 0;
        ok[c] = 0;
        owner[id] = -2;
      }
    }
  }
  // Each piece shared by at most two triangles, in opposite directions; the
  // boundary's vertices and their neighbours along it.
  std::vector<std::uint8_t> border_count(nv, 0);               // a vertex's boundary pieces (at most 2 kept)
  std::vector<std::array<std::uint32_t, 2>> border_next(nv);   // and its neighbours along them
  auto comp_of = [&](const WorldPiece& p) { return comp[static_cast<std::size_t>(p.sharers[0].facet)]; };
  for (const WorldPiece& p : pieces) {
    const auto& s = p.sharers;
    const std::uint32_t c = comp_of(p);
    if (!ok[c]) continue;
    Tally& t = tally[c];
    if (s.size() > 2 || (s.size() == 2 && s[0].forward == s[1].forward)) {
      ok[c] = 0;
      continue;
    }
    ++t.pieces;
    t.uses += static_cast<std::int64_t>(s.size());
    if (s.size() != 1) continue;
    ++t.border;
    t.border_vertex = p.a;
    for (const auto& [v, w] : {std::pair(p.a, p.b), std::pair(p.b, p.a)}) {
      if (border_count[v] == 2) ok[c] = 0;
      else border_next[v][border_count[v]++] = w;
    }
  }
  // A disk: every facet edge one piece, Euler characteristic 1, and its
  // boundary one loop (every vertex on it with two neighbours there).
  for (std::size_t c = 0; c < ncomp; ++c) {
    const Tally& t = tally[c];
    if (!ok[c]) continue;
    if (t.facets < 2 || t.uses != 3 * t.facets || t.border < 3 || t.vertices - t.pieces + t.facets != 1) {
      ok[c] = 0;
      continue;
    }
    std::uint32_t prev = t.border_vertex, at = border_next[prev][0];
    std::int64_t steps = 1;
    while (at != t.border_vertex && steps <= t.border) {
      if (border_count[at] != 2) break;
      const auto& b = border_next[at];
      const std::uint32_t next = b[0] == prev ? b[1] : b[0];
      prev = at;
      at = next;
      ++steps;
    }
    if (at != t.border_vertex || steps != t.border || border_count[t.border_vertex] != 2) ok[c] = 0;
  }

  // Geometry: the plane each is seen in.
  std::vector<Plane> plane(ncomp);
  for (std::size_t c = 0; c < ncomp; ++c)
    if (ok[c]) plane[c] = plane_of(tally[c].normal);
  // Every triangle turning positively in it; and each vertex's fan. Round an
  // inner vertex its triangles' link edges make cycles (each edge to it has one
  // triangle on either side), each going round it once or more (every triangle
  // turns positively): once in all, counted as the link edges crossing its
  // horizontal line upwards (half-open: a link vertex on the line counts
  // below), means one fan once round. (Facets in chunks, in parallel: a count
  // per vertex, which stops at 2.)
  std::vector<char> bad(n, 0);
  std::vector<std::uint8_t> round(nv, 0);
  const bool shared = threads > 1;
  parallel_chunks(static_cast<int>(n), 8192, threads, [&](int, Chunk r) {
    for (auto f = static_cast<std::size_t>(r.begin); f < static_cast<std::size_t>(r.end); ++f) {
      // (The corners of a facet some places ahead asked for now: each is a
      // cache miss, facets and vertices lying in different orders.)
      constexpr std::size_t ahead = 8;
      if (f + ahead < static_cast<std::size_t>(r.end))
        for (const std::uint32_t id : corners(f + ahead)) __builtin_prefetch(&world[id]);
      const std::uint32_t c = comp[f];
      if (!ok[c]) continue;
      const auto& v = corners(f);
      const Plane& pl = plane[c];
      const std::array<Point, 3> p{pl.at(world[v[0]]), pl.at(world[v[1]]), pl.at(world[v[2]])};
      if (CGAL::orientation(p[0], p[1], p[2]) != CGAL::LEFT_TURN) {
        bad[f] = 1;
        continue;
      }
      for (std::size_t k = 0; k < 3; ++k) {
        const double y = p[k].y();
        if (border_count[v[k]] != 0 || !(p[(k + 1) % 3].y() <= y && p[(k + 2) % 3].y() > y)) continue;
        if (!shared) {   // (one thread: no locked instruction, 1.5 M of them on a 10^6-triangle terrain)
          round[v[k]] = static_cast<std::uint8_t>(std::min(round[v[k]] + 1, 2));
          continue;
        }
        std::atomic_ref<std::uint8_t> count(round[v[k]]);
        std::uint8_t was = count.load(std::memory_order_relaxed);
        while (was < 2 && !count.compare_exchange_weak(was, static_cast<std::uint8_t>(was + 1), std::memory_order_relaxed)) {
        }
      }
    }
  });
  for (std::size_t f = 0; f < n; ++f)
    if (bad[f]) ok[comp[f]] = 0;
  // Round a boundary vertex, its triangles one fan from one of its boundary
  // neighbours to the other, turning less than once (its triangles listed).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> at_border;   // (vertex, facet)
  for (std::size_t f = 0; f < n; ++f)
    if (ok[comp[f]])
      for (const std::uint32_t id : corners(f)) {
        if (border_count[id] != 0) at_border.emplace_back(id, static_cast<std::uint32_t>(f));
        else if (round[id] != 1) ok[comp[f]] = 0;
      }
  std::sort(at_border.begin(), at_border.end());
  for (std::size_t i = 0; i < at_border.size();) {
    const std::uint32_t v = at_border[i].first;
    std::size_t j = i;
    while (j < at_border.size() && at_border[j].first == v) ++j;
    const std::size_t m = j - i;
    const std::uint32_t c = comp[at_border[i].second];
    if (ok[c]) {
      std::uint32_t a[kMaxStar], b[kMaxStar];
      bool fan = m <= kMaxStar && border_count[v] == 2;
      for (std::size_t t = 0; fan && t < m; ++t) {
        const auto& cv = corners(at_border[i + t].second);
        const std::size_t k = cv[0] == v ? 0 : cv[1] == v ? 1 : 2;
        a[t] = cv[(k + 1) % 3];
        b[t] = cv[(k + 2) % 3];
      }
      const Plane& pl = plane[c];
      if (!fan || !boundary_fan(m, [&](std::size_t t) { return a[t]; }, [&](std::size_t t) { return b[t]; },
                                pl.at(world[v]), border_next[v], world, pl))
        ok[c] = 0;
    }
    i = j;
  }

  // The boundary loop, in the plane: simple (the loops of the components left,
  // by component, each in piece order).
  std::vector<std::pair<std::uint32_t, std::array<std::uint32_t, 2>>> loops;
  for (const WorldPiece& p : pieces)
    if (p.sharers.size() == 1 && ok[comp_of(p)]) loops.push_back({comp_of(p), {p.a, p.b}});
  std::stable_sort(loops.begin(), loops.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::array<std::uint32_t, 2>> segments;
  for (std::size_t i = 0; i < loops.size();) {
    const std::uint32_t c = loops[i].first;
    segments.clear();
    for (; i < loops.size() && loops[i].first == c; ++i) segments.push_back(loops[i].second);
    if (!loop_is_simple(segments, world, plane[c])) ok[c] = 0;
  }

  for (std::size_t f = 0; f < n; ++f)
    if (ok[comp[f]]) out[f] = component[f];
  return out;
}

}  // namespace vismap::engine
