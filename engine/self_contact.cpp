#include "engine/self_contact.h"

#include <CGAL/Bbox_3.h>
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

using K = CGAL::Epick;   // (predicates only: exact)
using Point = K::Point_3;

struct Triangle {
  std::array<std::uint32_t, 3> v;       // canonical vertex ids
  std::array<std::uint32_t, 3> local;   // the same, numbered 0, 1, ... within the component
  std::array<const Vec3*, 3> corner;
  int facet;
};

// The fans of the facets, without the triangles whose corners are collinear
// (those lie on their facet's border, which its other triangles hold), in facet
// order, made in chunks on `threads` threads; their local numbers are set by
// `numbered` below.
std::vector<Triangle> fan_triangles(const Scene& scene, const WorldFacets& wf, const std::vector<int>& facets,
                                    int threads) {
  std::size_t most = 0;
  for (int fi : facets) most += wf.facets[static_cast<std::size_t>(fi)].v.size() - 2;
  std::vector<Triangle> tris;
  tris.reserve(most);   // (one block: grown push by push, its pages were zeroed again and again)
  const int n = static_cast<int>(facets.size()), size = 2048;
  parallel_append(tris, chunk_count(n, size), threads, [&](int c, std::vector<Triangle>& out) {
    const Chunk r = chunk(c, n, size);
    for (int i = r.begin; i < r.end; ++i) {
      const int fi = facets[static_cast<std::size_t>(i)];
      const auto& v = wf.facets[static_cast<std::size_t>(fi)].v;
      for (std::size_t k = 1; k + 1 < v.size(); ++k)
        if (!world::collinear(scene.vertices[v[0]], scene.vertices[v[k]], scene.vertices[v[k + 1]]))
          out.push_back({{v[0], v[k], v[k + 1]},
                         {},
                         {&scene.vertices[v[0]], &scene.vertices[v[k]], &scene.vertices[v[k + 1]]},
                         fi});
    }
  });
  return tris;
}

// The fans of `tris` with their vertices numbered 0, 1, ... in order of first
// use by `local(id, count)` (which gives a new one the number count, then
// counted), and how many vertices they have.
struct Fans {
  std::vector<Triangle> tris;
  std::uint32_t vertices = 0;
};
template <class Local>
Fans numbered(std::vector<Triangle> tris, Local&& local) {
  Fans out;
  out.tris = std::move(tris);
  for (Triangle& t : out.tris)
    for (std::size_t k = 0; k < 3; ++k) t.local[k] = local(t.v[k], out.vertices);
  return out;
}
// Numbered through `slot` (per canonical id, ~0u), which is left as it was found.
Fans fans(const Scene& scene, const WorldFacets& wf, const std::vector<int>& facets, std::vector<std::uint32_t>& slot,
          int threads) {
  Fans out = numbered(fan_triangles(scene, wf, facets, threads), [&](std::uint32_t id, std::uint32_t& count) {
    if (slot[id] == ~0u) slot[id] = count++;
    return slot[id];
  });
  for (const Triangle& t : out.tris)
    for (auto id : t.v) slot[id] = ~0u;
  return out;
}
// Numbered through a sorted list of the facets' vertex ids (a small component,
// on a thread of its own: no table the size of the scene).
Fans fans(const Scene& scene, const WorldFacets& wf, const std::vector<int>& facets) {
  std::vector<std::uint32_t> ids;
  for (int fi : facets)
    for (auto id : wf.facets[static_cast<std::size_t>(fi)].v) ids.push_back(id);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  // (Numbers by rank among the ids, then made consecutive in order of use.)
  std::vector<std::uint32_t> slot(ids.size(), ~0u);
  return numbered(fan_triangles(scene, wf, facets, 1), [&](std::uint32_t id, std::uint32_t& count) {
    std::uint32_t& s = slot[static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin())];
    if (s == ~0u) s = count++;
    return s;
  });
}

// Vertex stars that lie flat along a coordinate axis. On a mesh, nearly every
// pair of triangles whose boxes meet are neighbours sharing a corner v. Where
// the triangles around v, seen along one coordinate axis, each have a
// non-zero area and go round v exactly once (their link edges make one cycle
// of winding number 1 about v), their projections tile a disk around v, each
// within its own angle: two of them meet on the projection only at v or along
// a common edge, and since the projection is one to one on each of them, so
// do they. One test per vertex answers all its pairs (as EmbeddedStars does on
// the screen: engine/embedded_stars.h); only the axis and coordinates differ.
// Exact: orientations and comparisons of input doubles.
class FlatStars {
 public:
  FlatStars(const Fans& fans, int threads) : flat_(fans.vertices, 0) {
    // Each vertex's triangles (compressed rows, by local number).
    const std::vector<Triangle>& tris = fans.tris;
    const std::size_t vertices = fans.vertices;
    std::vector<std::uint32_t> first(vertices + 1, 0);
    for (const Triangle& t : tris)
      for (auto v : t.local) ++first[v + 1];
    for (std::size_t v = 0; v < vertices; ++v) first[v + 1] += first[v];
    std::vector<std::uint32_t> at(first.begin(), first.end() - 1), of(first.back());
    for (std::size_t i = 0; i < tris.size(); ++i)
      for (auto v : tris[i].local) of[at[v]++] = static_cast<std::uint32_t>(i);
    parallel_chunks(static_cast<int>(vertices), 4096, threads, [&](int, Chunk r) {
      for (auto v = static_cast<std::size_t>(r.begin); v < static_cast<std::size_t>(r.end); ++v)
        if (first[v + 1] > first[v]) flat_[v] = flat(tris, v, of.data() + first[v], first[v + 1] - first[v]);
    });
  }
  // Whether the star of the vertex numbered v (Triangle::local) is flat: then
  // two of its triangles meet only at v and along an edge they share.
  bool at(std::uint32_t v) const { return flat_[v] != 0; }

 private:
  struct Link {   // the side a -> b of a triangle (v, a, b) turning positively
    const Vec3* a;   // (a's point; b's is the next link's a)
    std::uint32_t ia, ib;
  };
  static bool flat(const std::vector<Triangle>& tris, std::size_t v, const std::uint32_t* star, std::size_t n) {
    if (n < 3 || n > kMaxStar) return false;   // (as goes_round_once would say)
    // The axis to look along: the first triangle's normal's largest component
    // (doubles: any axis gives an exact answer; this one makes flat stars likely).
    const Triangle& t0 = tris[star[0]];
    const auto nv = world::normal_of<double>(*t0.corner[0], *t0.corner[1], *t0.corner[2]);
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(nv[static_cast<std::size_t>(k)]) > std::abs(nv[static_cast<std::size_t>(axis)])) axis = k;
    const int ux = (axis + 1) % 3, uy = (axis + 2) % 3;
    auto xy = [&](const Vec3& p) { return CGAL::Epick::Point_2(coordinate(p, ux), coordinate(p, uy)); };
    Link e[kMaxStar];
    const Vec3* centre = nullptr;
    for (std::size_t i = 0; i < n; ++i) {
      const Triangle& t = tris[star[i]];
      const std::size_t k = t.local[0] == v ? 0 : t.local[1] == v ? 1 : 2;
      const std::size_t ka = (k + 1) % 3, kb = (k + 2) % 3;
      centre = t.corner[k];
      const CGAL::Orientation o = CGAL::orientation(xy(*t.corner[k]), xy(*t.corner[ka]), xy(*t.corner[kb]));
      if (o == CGAL::COLLINEAR) return false;
      e[i] = o == CGAL::LEFT_TURN ? Link{t.corner[ka], t.v[ka], t.v[kb]} : Link{t.corner[kb], t.v[kb], t.v[ka]};
    }
    // Going round v once, seen along the axis (engine/star_link.h).
    const double y = coordinate(*centre, uy);
    return goes_round_once(
        n, [&](std::size_t i) { return e[i].ia; }, [&](std::size_t i) { return e[i].ib; },
        [&](std::size_t i) { return coordinate(*e[i].a, uy) <= y; });
  }
  std::vector<char> flat_;
};

// What the pair search reads of a triangle beside its box, to pass over the
// pairs that cannot meet elsewhere without looking further: its corners, its
// facet, and which corners' stars are flat.
struct Corners {
  std::array<std::uint32_t, 3> v;   // canonical vertex ids
  int facet;
  std::uint8_t flat;                // bit k: corner k's star is flat (FlatStars)
};

// Whether two triangles meet only where they share corners and edges, known
// without arithmetic: they belong to one facet, or share a corner whose star is flat.
bool known_apart(const Corners& a, const Corners& b) {
  if (a.facet == b.facet) return true;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto u = a.v[k];
    if ((a.flat >> k & 1) && (u == b.v[0] || u == b.v[1] || u == b.v[2])) return true;
  }
  return false;
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

// At most this many boxes: every pair, no grid (any_box_pair).
constexpr std::size_t kFewBoxes = 32;

// Pairs of boxes that meet (closed boxes), each once, until `f` returns true,
// but those that skip(key, key) passes over: a uniform grid of about one cell
// per box, each box listed in the cells it meets; a pair is taken in the cell
// of the lower corner of its common box. Chunks of cells on `threads` threads
// (the answer is whether any pair does: the same whichever finds it).
template <class Key, class Skip, class F>
bool any_box_pair(const std::vector<CGAL::Bbox_3>& boxes, const std::vector<Key>& keys, int threads, Skip&& skip,
                  F&& f) {
  const std::size_t n = boxes.size();
  if (n < 2) return false;
  // A few boxes (a box of a city or of a lattice: 12 triangles): every pair,
  // each asked as the sweep below would (the lower x first), with no grid:
  // its cells and lists cost more than the pairs (the generated building's
  // 4 840 boxes: 26 000 instructions each, an eighth of a view).
  if (n <= kFewBoxes) {
    for (std::uint32_t i = 0; i < n; ++i)
      for (std::uint32_t j = i + 1; j < n; ++j) {
        const bool i_first = boxes[i].xmin() <= boxes[j].xmin();   // (equal: the lower index, i)
        const std::uint32_t s = i_first ? i : j, t = i_first ? j : i;
        if (CGAL::do_overlap(boxes[s], boxes[t]) && !skip(keys[s], keys[t]) && f(s, t)) return true;
      }
    return false;
  }
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
  // Each box's cells, lowest and highest in each axis (the cell of a common
  // box's lower corner is the larger of the two boxes' lowest in each axis:
  // cell() is monotone).
  struct Cells {
    int lo[3], hi[3];
  };
  std::vector<Cells> range(n);
  parallel_chunks(static_cast<int>(n), 16384, threads, [&](int, Chunk r) {
    for (auto i = static_cast<std::size_t>(r.begin); i < static_cast<std::size_t>(r.end); ++i) {
      const CGAL::Bbox_3& b = boxes[i];
      for (int k = 0; k < 3; ++k) {
        range[i].lo[k] = cell(k, b.min(k));
        range[i].hi[k] = cell(k, b.max(k));
      }
    }
  });
  auto for_cells = [&](const Cells& r, auto&& visit) {
    for (int z = r.lo[2]; z <= r.hi[2]; ++z)
      for (int y = r.lo[1]; y <= r.hi[1]; ++y)
        for (int x = r.lo[0]; x <= r.hi[0]; ++x) visit(index(x, y, z));
  };
  const std::size_t cells = static_cast<std::size_t>(g[0]) * g[1] * g[2];
  Buckets in_cell = bucket_items(static_cast<int>(n), cells, threads, [&](int i, auto&& visit) {
    for_cells(range[static_cast<std::size_t>(i)], visit);
  });
  const std::vector<std::uint32_t>& start = in_cell.first;
  std::vector<std::uint32_t>& member = in_cell.items;
  // In each cell, its boxes by their lower x: a box meets only those after it
  // that start before it ends. (Copied side by side first, with their keys and
  // whether each starts in this cell along each axis: a pair's home is this
  // cell when, along every axis, one of the two starts here. The sweep then
  // reads one array in order; the boxes' own places only for the pairs f is
  // asked about.)
  struct Entry {
    CGAL::Bbox_3 box;
    Key key;
    std::uint32_t item;
    std::uint8_t starts;   // bit k: the box's lowest cell along axis k is this cell's
  };
  std::atomic<bool> found{false};
  parallel_chunks(static_cast<int>(cells), 1024, threads, [&](int, Chunk r) {
    std::vector<Entry> here;
    for (auto c = static_cast<std::size_t>(r.begin); c < static_cast<std::size_t>(r.end); ++c) {
      if (found.load(std::memory_order_relaxed)) return;
      if (start[c + 1] - start[c] < 2) continue;
      const auto gx = static_cast<std::size_t>(g[0]), gy = static_cast<std::size_t>(g[1]);
      const std::size_t at[3] = {c % gx, c / gx % gy, c / (gx * gy)};   // (index()'s x, y, z)
      const auto first = member.begin() + start[c], last = member.begin() + start[c + 1];
      std::sort(first, last, [&](std::uint32_t i, std::uint32_t j) {
        return boxes[i].xmin() < boxes[j].xmin() || (boxes[i].xmin() == boxes[j].xmin() && i < j);
      });
      here.clear();
      for (auto m = first; m != last; ++m) {
        const std::uint32_t i = *m;
        std::uint8_t starts = 0;
        for (int a = 0; a < 3; ++a)
          if (static_cast<std::size_t>(range[i].lo[a]) == at[a]) starts |= static_cast<std::uint8_t>(1u << a);
        here.push_back(Entry{boxes[i], keys[i], i, starts});
      }
      for (auto s = here.begin(); s != here.end(); ++s) {
        const CGAL::Bbox_3& a = s->box;
        for (auto t = s + 1; t != here.end() && t->box.xmin() <= a.xmax(); ++t) {
          const CGAL::Bbox_3& b = t->box;
          if (a.ymax() < b.ymin() || b.ymax() < a.ymin() || a.zmax() < b.zmin() || b.zmax() < a.zmin()) continue;
          if ((s->starts | t->starts) != 7 || skip(s->key, t->key)) continue;
          if (f(s->item, t->item)) {
            found.store(true, std::memory_order_relaxed);
            return;
          }
        }
      }
    }
  });
  return found.load();
}

// Whether the triangles of one component meet other than where they share corners.
bool meets(const Fans& fans, int threads) {
  const std::vector<Triangle>& tris = fans.tris;
  // Each triangle's box, and its normal once for the side tests, in chunks.
  const int n = static_cast<int>(tris.size()), size = 4096;
  std::vector<CGAL::Bbox_3> boxes;
  std::vector<world::PlaneSide> planes;
  boxes.reserve(tris.size());
  planes.reserve(tris.size());
  parallel_append(boxes, chunk_count(n, size), threads, [&](int c, std::vector<CGAL::Bbox_3>& out) {
    const Chunk r = chunk(c, n, size);
    for (int i = r.begin; i < r.end; ++i) {
      CGAL::Bbox_3 b;
      for (const Vec3* p : tris[static_cast<std::size_t>(i)].corner)
        b += CGAL::Bbox_3(p->x, p->y, p->z, p->x, p->y, p->z);
      out.push_back(b);
    }
  });
  parallel_append(planes, chunk_count(n, size), threads, [&](int c, std::vector<world::PlaneSide>& out) {
    const Chunk r = chunk(c, n, size);
    for (int i = r.begin; i < r.end; ++i) {
      const Triangle& t = tris[static_cast<std::size_t>(i)];
      out.emplace_back(*t.corner[0], *t.corner[1], *t.corner[2]);
    }
  });
  const FlatStars stars(fans, threads);
  std::vector<Corners> corners;
  corners.reserve(tris.size());
  parallel_append(corners, chunk_count(n, size), threads, [&](int c, std::vector<Corners>& out) {
    const Chunk r = chunk(c, n, size);
    for (int i = r.begin; i < r.end; ++i) {
      const Triangle& t = tris[static_cast<std::size_t>(i)];
      std::uint8_t flat = 0;
      for (std::size_t k = 0; k < 3; ++k)
        if (stars.at(t.local[k])) flat |= static_cast<std::uint8_t>(1u << k);
      out.push_back(Corners{t.v, t.facet, flat});
    }
  });
  return any_box_pair(boxes, corners, threads, known_apart, [&](std::uint32_t i, std::uint32_t j) {
    return meet(tris[i], tris[j], planes[i], planes[j]);
  });
}

}  // namespace

std::vector<char> meets_itself(const Scene& scene, const WorldFacets& wf, const std::vector<std::vector<int>>& components,
                               int threads) {
  // Large components one after another, each on the threads; small ones (a
  // city's buildings, a lattice of boxes: thousands of them) side by side, each
  // on one thread (a loop on the threads for each cost more than its test).
  constexpr std::size_t kLarge = 4096;   // facets
  std::vector<char> out(components.size(), 0);
  std::vector<std::uint32_t> slot;   // (one table for the large ones, left as found)
  std::vector<int> small;
  for (std::size_t k = 0; k < components.size(); ++k) {
    if (components[k].size() < kLarge) { small.push_back(static_cast<int>(k)); continue; }
    if (slot.empty()) slot.assign(scene.vertices.size(), ~0u);
    out[k] = meets(fans(scene, wf, components[k], slot, threads), threads);
  }
  parallel_chunks(static_cast<int>(small.size()), 64, threads, [&](int, Chunk r) {
    for (int i = r.begin; i < r.end; ++i) {
      const auto k = static_cast<std::size_t>(small[static_cast<std::size_t>(i)]);
      out[k] = meets(fans(scene, wf, components[k]), 1);
    }
  });
  return out;
}

bool meets_itself(const Scene& scene, const WorldFacets& wf, const std::vector<int>& facets, int threads) {
  return meets_itself(scene, wf, std::vector<std::vector<int>>{facets}, threads)[0] != 0;
}

}  // namespace vismap::engine
