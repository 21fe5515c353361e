#include <algorithm>
#include <atomic>
#include <climits>
#include <numeric>
#include <stdexcept>
#include <tuple>

#include "arrangements/map_graph.h"
#include "engine/parallel.h"

namespace vismap {
VISMAP_KERNEL_BEGIN
namespace {

using namespace exact;

// sign(depth of m - depth of w) at the midpoint of a and b, the end points of
// both (coincident pieces of one map edge): their lines hold that point, so
// each depth is its line's at the point's x (or y, where x does not move along
// it), as depth_along gives it. On intervals, else exactly; no lazy number is
// built (coincident lines, on scenes of aligned parts: hundreds of thousands).
CGAL::Sign depth_order_at_middle(const MapPiece& m, const MapPiece& w, const P2& a, const P2& b) {
  return filtered_sign(
      [&] {
        const Interval mx = (approx_x(a) + approx_x(b)) / 2, my = (approx_y(a) + approx_y(b)) / 2;
        auto depth = [&](const MapPiece& p) {
          const Interval dx = approx_of(p.t->x) - approx_of(p.s->x), dy = approx_of(p.t->y) - approx_of(p.s->y);
          // (Along x where its difference is apart from 0 and the larger; a
          // difference reaching 0 on both gives an unbounded interval: exact.)
          const bool use_x = !dx.do_overlap(0) && (dy.do_overlap(0) || CGAL::abs(dx).inf() >= CGAL::abs(dy).inf());
          const Interval lambda =
              use_x ? (mx - approx_of(p.s->x)) / dx : (my - approx_of(p.s->y)) / dy;
          return approx_of(p.s->z) + lambda * (approx_of(p.t->z) - approx_of(p.s->z));
        };
        return depth(m) - depth(w);
      },
      [&]() -> mpq_class {
        const mpq_class mx = (exact_x(a) + exact_x(b)) / 2, my = (exact_y(a) + exact_y(b)) / 2;
        auto depth = [&](const MapPiece& p) {
          const mpq_class sx = to_mpq(p.s->x), sy = to_mpq(p.s->y), sz = to_mpq(p.s->z);
          const mpq_class dx = to_mpq(p.t->x) - sx;
          const mpq_class lambda = dx != 0 ? mpq_class((mx - sx) / dx) : mpq_class((my - sy) / (to_mpq(p.t->y) - sy));
          return mpq_class(sz + lambda * (to_mpq(p.t->z) - sz));
        };
        return depth(m) - depth(w);
      });
}

// Canonical start: the rotation that is lexicographically smallest (vertex
// numbers follow the points' lexicographic order).
void rotate_canonical(std::vector<int>& ring) {
  std::size_t best = 0;
  const std::size_t n = ring.size();
  for (std::size_t i = 1; i < n; ++i) {
    for (std::size_t k = 0; k < n; ++k) {
      const int a = ring[(i + k) % n], b = ring[(best + k) % n];
      if (a < b) { best = i; break; }
      if (b < a) break;
    }
  }
  std::rotate(ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(best), ring.end());
}

// Vertices of the arrangement that are vertices of the canonical map: where
// other than two edges meet, or two that differ or bend (an edge that is not
// drawn and has the same face on both sides is no edge of the arrangement: it
// only kept a farther line from being drawn). `two`: where a vertex has two
// edges, those two (in either order: every use takes them as a pair).
struct Essential {
  std::vector<char> essential;
  std::vector<int> two;
};
Essential essential_vertices(const MapGraph& g, int threads) {
  const int nedges = static_cast<int>(g.ends.size()), nverts = static_cast<int>(g.points.size());
  auto inert = [&](int e) { return !g.attrs[e].drawn && g.attrs[e].left == g.attrs[e].right; };
  std::vector<int> degree(nverts, 0);
  Essential out;
  out.two.assign(2 * static_cast<std::size_t>(nverts), -1);
  // Each vertex's edges counted, its first two kept (by whichever thread comes first).
  engine::parallel_chunks(nedges, 16384, threads, [&](int, engine::Chunk r) {
    for (int e = r.begin; e < r.end; ++e)
      if (!inert(e))
        for (int w : g.ends[e])
          if (const int k = std::atomic_ref<int>(degree[w]).fetch_add(1, std::memory_order_relaxed); k < 2)
            out.two[2 * static_cast<std::size_t>(w) + static_cast<std::size_t>(k)] = e;
  });
  auto other_end = [&](int e, int w) { return g.ends[e][0] == w ? g.ends[e][1] : g.ends[e][0]; };
  // A vertex where two collinear edges of the same attributes meet is not a
  // vertex. (Pieces of one curve are collinear by construction: the exact zero
  // that no filter settles is then never asked.) Where only the points can tell,
  // they are asked afterwards, in vertex order on one thread: a lazy point's
  // interval narrows once its exact value is made, so the order decides which
  // later predicates need one, and the counts must not depend on the threads.
  out.essential.assign(nverts, 1);
  std::vector<char> ask(static_cast<std::size_t>(nverts), 0);
  engine::parallel_chunks(nverts, 16384, threads, [&](int, engine::Chunk r) {
    for (int w = r.begin; w < r.end; ++w)
      if (degree[w] == 2) {
        const EdgeAttr &a1 = g.attrs[out.two[2 * w]], &a2 = g.attrs[out.two[2 * w + 1]];
        if (!a1.same_as(a2)) continue;
        if (a1.line >= 0 && a1.line == a2.line) out.essential[w] = 0;
        else ask[w] = 1;
      }
  });
  for (int w = 0; w < nverts; ++w)
    if (ask[w]) {   // (the orientation's sign does not depend on which edge is the first)
      const int e1 = out.two[2 * w], e2 = out.two[2 * w + 1];
      out.essential[w] =
          CGAL::orientation(g.points[other_end(e1, w)], g.points[w], g.points[other_end(e2, w)]) != CGAL::COLLINEAR;
    }
  return out;
}

// A vertex's exact coordinates.
Point2 exact_point(const MapGraph& g, int w) {
  const auto& ap = g.approx[w];
  if (ap.x().is_point() && ap.y().is_point())
    // An interval of one double holds the exact value: no exact evaluation
    // (crossings of axis-parallel lines, input vertices in axis views).
    return Point2{mpq_class(ap.x().inf()), mpq_class(ap.y().inf())};
  const auto& e = CGAL::exact(g.points[w]);
  return Point2{to_mpq(e.x()), to_mpq(e.y())};
}

// Segments: maximal chains of drawn edges through superfluous vertices, each
// walked from its smaller end (halfedges 2e run that way). Their ends are marked written.
struct Chain {
  int from, to, edge;
};
std::vector<Chain> drawn_chains(const MapGraph& g, const Essential& ess, std::vector<char>& written, int threads) {
  auto target = [&](int h) { return g.ends[h >> 1][(h & 1) ^ 1]; };
  auto mark = [&](int w) {
    std::atomic_ref<char>(written[static_cast<std::size_t>(w)]).store(1, std::memory_order_relaxed);
  };
  const int nedges = static_cast<int>(g.ends.size()), size = 16384;
  std::vector<Chain> chains;
  engine::parallel_append(chains, engine::chunk_count(nedges, size), threads, [&](int c, std::vector<Chain>& out) {
    const engine::Chunk r = engine::chunk(c, nedges, size);
    for (int e = r.begin; e < r.end; ++e) {
      const EdgeAttr& a = g.attrs[e];
      if (!a.drawn || !ess.essential[g.ends[e][0]]) continue;   // hidden, or not the start of its chain
      int cur = 2 * e;
      while (!ess.essential[target(cur)]) {
        const int w = target(cur), here = cur >> 1;
        const int o = ess.two[2 * w] == here ? ess.two[2 * w + 1] : ess.two[2 * w];
        cur = g.ends[o][0] == w ? 2 * o : 2 * o + 1;
      }
      out.push_back(Chain{g.ends[e][0], target(cur), e});
      mark(g.ends[e][0]);
      mark(target(cur));
    }
  });
  return chains;
}

// The written vertices, once each, numbered in vertex (lexicographic) order;
// rings and segments refer to them by number, so canonical order is kept.
// Returns each graph vertex's number in map.vertices.
// Their exact values, each in its own slot, in chunks on `threads` threads (most
// are lazy points evaluated here for the first time).
std::vector<std::uint32_t> write_vertices(const MapGraph& g, const std::vector<char>& written, VisibilityMap& map,
                                          int threads) {
  const int nverts = static_cast<int>(g.points.size());
  const std::vector<int> at =   // the written vertices, in order
      engine::indices_where(nverts, threads, [&](int w) { return written[static_cast<std::size_t>(w)] != 0; });
  std::vector<std::uint32_t> index(g.points.size(), 0);
  engine::parallel_chunks(static_cast<int>(at.size()), 16384, threads, [&](int, engine::Chunk r) {
    for (int i = r.begin; i < r.end; ++i)
      index[static_cast<std::size_t>(at[static_cast<std::size_t>(i)])] = static_cast<std::uint32_t>(i);
  });
  map.vertices.resize(at.size());
  const int n = static_cast<int>(at.size()), size = 512;   // (~1 us a vertex: chunks that share out evenly)
  engine::parallel_chunks(n, size, threads, [&](int, engine::Chunk r) {
    for (int i = r.begin; i < r.end; ++i)
      map.vertices[static_cast<std::size_t>(i)] = exact_point(g, at[static_cast<std::size_t>(i)]);
  });
  return index;
}

void write_segments(const MapGraph& g, std::vector<Chain> chains, const std::vector<std::uint32_t>& index,
                    VisibilityMap& map, int threads) {
  // (Two straight chains never join the same two vertices; the edge settles
  // the order all the same, so that no thread count could change it.)
  engine::parallel_sort(chains.begin(), chains.end(), [](const Chain& a, const Chain& b) {
    return std::tuple(a.from, a.to, a.edge) < std::tuple(b.from, b.to, b.edge);
  }, threads);
  map.segments.resize(chains.size());
  engine::parallel_chunks(static_cast<int>(chains.size()), 4096, threads, [&](int, engine::Chunk r) {
    for (int i = r.begin; i < r.end; ++i) {
      // The faces lists lie with the engine's curves, in another order: fetch ahead.
      if (i + 16 < r.end) __builtin_prefetch(g.attrs[chains[static_cast<std::size_t>(i) + 16].edge].faces);
      const Chain& c = chains[static_cast<std::size_t>(i)];
      const FacesList& faces = *g.attrs[c.edge].faces;
      map.segments[static_cast<std::size_t>(i)] =
          Segment{index[c.from], index[c.to], g.attrs[c.edge].kind, {faces.begin(), faces.end()}};
    }
  });
}

// The ring of boundary halfedges from h0 (succ: the next one along its
// region): its essential vertices from the canonical start, and whether it
// turns counter-clockwise (an outer ring: its signed area positive, on
// intervals, exactly where they cannot tell).
void trace_ring(const MapGraph& g, const Essential& ess, const std::vector<int>& succ, int h0, std::vector<int>& ring,
                bool& outer) {
  auto source = [&](int h) { return g.ends[h >> 1][h & 1]; };
  auto target = [&](int h) { return g.ends[h >> 1][(h & 1) ^ 1]; };
  Interval area = 0;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    int h = h0;
    do {
      if (ess.essential[source(h)]) ring.push_back(source(h));
      const auto &p = g.approx[source(h)], &q = g.approx[target(h)];
      area += p.x() * q.y() - q.x() * p.y();
      h = succ[h];
    } while (h != h0);
  }
  outer = area.inf() > 0;
  if (area.inf() <= 0 && area.sup() > 0) {
    mpq_class s2 = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point2 p = exact_point(g, ring[i]), q = exact_point(g, ring[(i + 1) % ring.size()]);
      s2 += p.x * q.y - q.x * p.y;
    }
    outer = sgn(s2) > 0;
  }
  rotate_canonical(ring);
}

// A boundary ring: its essential vertices from the canonical start, and its turn.
struct Traced {
  std::vector<int> ring;
  bool outer = false;   // counter-clockwise
};

// The rings bounding the regions (faces of one label joined: `label` per face,
// -1 outside the map): each boundary halfedge's successor along its region
// (stepping over edges inside it), then the rings numbered in order of their
// first halfedge (a walk: cheap; `first`), then each ring traced (the costly
// part) in parallel.
std::vector<Traced> boundary_rings(const MapGraph& g, const std::vector<int>& label, const Essential& ess,
                                   std::vector<int>& first, int threads) {
  const int nhalf = static_cast<int>(2 * g.ends.size());
  auto boundary = [&](int h) { return label[g.face[h]] != label[g.face[h ^ 1]]; };
  std::vector<int> succ(nhalf, -1);
  engine::parallel_chunks(nhalf, 16384, threads, [&](int, engine::Chunk r) {
    for (int h = r.begin; h < r.end; ++h) {
      if (label[g.face[h]] < 0 || !boundary(h)) continue;
      int nx = g.next[h];
      while (!boundary(nx)) nx = g.next[nx ^ 1];
      succ[h] = nx;
    }
  });
  std::vector<char> visited(nhalf, 0);
  for (int h0 = 0; h0 < nhalf; ++h0) {
    if (succ[h0] < 0 || visited[h0]) continue;
    first.push_back(h0);
    for (int h = h0; !visited[h]; h = succ[h]) visited[h] = 1;
  }
  std::vector<Traced> traced(first.size());
  engine::parallel_chunks(static_cast<int>(first.size()), 1024, threads, [&](int, engine::Chunk r) {
    for (int k = r.begin; k < r.end; ++k) trace_ring(g, ess, succ, first[k], traced[k].ring, traced[k].outer);
  });
  return traced;
}

}  // namespace

EdgeAttr edge_attr(const std::vector<MapPiece>& pieces, const int* on_edge, std::size_t count, const P2& a,
                   const P2& b) {
  EdgeAttr at;
  const MapPiece& any = pieces[on_edge[0]];
  at.left = any.left;
  at.right = any.right;
  at.line = any.line;
  int winner = -1;
  for (std::size_t k = 0; k < count; ++k) {
    const int pi = on_edge[k];
    const MapPiece& m = pieces[pi];
    // Every visible piece competes, drawn or not: a nearer smooth seam covers a
    // farther border under it, and then nothing is drawn there.
    if (!m.visible) continue;
    if (winner < 0) { winner = pi; continue; }
    const MapPiece& w = pieces[winner];
    const CGAL::Sign c = depth_order_at_middle(m, w, a, b);
    // Ties in (depth, lowest face index), e.g. two intersection lines of one face
    // along one 3D line: the faces lists, lexicographically, so that the written
    // segment does not depend on the order the pieces came in.
    if (c == CGAL::NEGATIVE ||
        (c == CGAL::ZERO && (m.order_face < w.order_face ||
                              (m.order_face == w.order_face && *m.faces < *w.faces))))
      winner = pi;
  }
  if (winner >= 0 && pieces[winner].drawn) {
    at.drawn = true;
    at.kind = pieces[winner].kind;
    at.faces = pieces[winner].faces;
  }
  return at;
}

void write_canonical(const MapGraph& g, VisibilityMap& map, int threads) {
  const int nedges = static_cast<int>(g.ends.size());
  const int nhalf = 2 * nedges;
  const int nverts = static_cast<int>(g.points.size());

  // Face labels from the halfedges around them; they must all agree.
  std::vector<int> label(g.faces, INT_MIN);
  if (g.unbounded >= 0) label[g.unbounded] = -1;
  for (int h = 0; h < nhalf; ++h) {
    const EdgeAttr& a = g.attrs[h >> 1];
    const int x = (h & 1) == 0 ? a.left : a.right;
    int& l = label[g.face[h]];
    if (l == INT_MIN) l = x;
    else if (l != x) throw std::logic_error("visibility map: inconsistent face labels (engine bug)");
  }

  const Essential ess = essential_vertices(g, threads);
  std::vector<char> written(nverts, 0);

  // Regions: faces of one label joined across edges that separate nothing.
  // Rings are kept as vertex numbers until the end.
  UnionFind groups(g.faces);
  for (int e = 0; e < nedges; ++e)
    if (label[g.face[2 * e]] == label[g.face[2 * e + 1]]) groups.join(g.face[2 * e], g.face[2 * e + 1]);
  struct Rings {
    int face = -1;
    std::vector<int> outer;
    std::vector<std::vector<int>> holes;
  };
  std::vector<int> first;   // ring -> its first halfedge
  std::vector<Traced> traced = boundary_rings(g, label, ess, first, threads);
  std::vector<int> slot(g.faces, -1);   // group -> index in `found`
  std::vector<Rings> found;
  for (std::size_t k = 0; k < first.size(); ++k) {
    const int h0 = first[k];
    std::vector<int>& ring = traced[k].ring;
    for (int w : ring) written[w] = 1;
    int& at = slot[groups.find(g.face[h0])];
    if (at < 0) { at = static_cast<int>(found.size()); found.emplace_back(); }
    Rings& r = found[at];
    r.face = label[g.face[h0]];
    if (traced[k].outer) {
      if (!r.outer.empty()) throw std::logic_error("visibility map: region with two outer rings (engine bug)");
      r.outer = std::move(ring);
    } else {
      r.holes.push_back(std::move(ring));
    }
  }
  std::vector<Traced>().swap(traced);
  for (Rings& r : found) {
    if (r.outer.empty()) throw std::logic_error("visibility map: region without outer ring (engine bug)");
    std::sort(r.holes.begin(), r.holes.end());
  }
  // (No two regions of one face have one outer ring: the order is total, and the
  // same for every thread count.)
  engine::parallel_sort(found.begin(), found.end(), [](const Rings& a, const Rings& b) {
    if (a.face != b.face) return a.face < b.face;
    return a.outer < b.outer;
  }, threads);
  std::vector<Chain> chains = drawn_chains(g, ess, written, threads);
  const std::vector<std::uint32_t> index = write_vertices(g, written, map, threads);
  auto ring_of = [&](const std::vector<int>& ids) {
    Ring out;
    out.reserve(ids.size());
    for (int w : ids) out.push_back(index[w]);
    return out;
  };
  map.regions.resize(found.size());
  engine::parallel_chunks(static_cast<int>(found.size()), 4096, threads, [&](int, engine::Chunk c) {
    for (int i = c.begin; i < c.end; ++i) {
      const Rings& r = found[static_cast<std::size_t>(i)];
      Region& out = map.regions[static_cast<std::size_t>(i)];
      out.face = r.face;
      out.outer = ring_of(r.outer);
      for (const auto& hole : r.holes) out.holes.push_back(ring_of(hole));
    }
  });

  write_segments(g, std::move(chains), index, map, threads);
}

void write_segments_only(const MapGraph& g, VisibilityMap& map, int threads) {
  std::vector<char> written(g.points.size(), 0);
  const std::vector<Chain> chains = drawn_chains(g, essential_vertices(g, threads), written, threads);
  write_segments(g, chains, write_vertices(g, written, map, threads), map, threads);
  map.has_regions = false;
}

VISMAP_KERNEL_END
}  // namespace vismap
