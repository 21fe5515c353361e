#include "engine/edge_pieces.h"

#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <tuple>

#include "engine/parallel.h"

namespace vismap::engine {
namespace {

// (16 bytes, and no coordinates: grouping edges reads no vertex. Which way an
// edge runs is its group's business: LineDir.)
struct Edge {
  int facet;
  std::uint32_t edge;   // a convex planar polygon is one facet of up to 10^6 corners
  std::uint32_t p, q;   // vertex ids, facet order
};

// The line through two distinct points: the first axis along which it moves,
// and whether it moves up that axis from the first point to the second.
struct LineDir {
  std::uint8_t axis;
  bool up;
};
LineDir line_dir(const Vec3& a, const Vec3& b) {
  const std::uint8_t axis = a.x != b.x ? 0 : a.y != b.y ? 1 : 2;
  return {axis, coordinate(a, axis) < coordinate(b, axis)};
}

// The supporting line of p->q as an exact canonical key: the first axis k along
// which the line moves, the slopes d_j/d_k and the offsets at x_k = 0, as
// fractions over one positive denominator d_k, in binary floats: sums and
// products of the input's doubles (CGAL::Mpzf, no gcd), compared by cross
// multiplication. (The same values whichever end the line is taken from.)
struct LineKey {
  int axis = 0;
  std::array<CGAL::Mpzf, 4> num;   // r[i] = num[i] / den: the two slopes, then the two offsets
  CGAL::Mpzf den;                  // > 0
};

LineKey line_key(const Vec3& p, const Vec3& q, int k) {
  using M = CGAL::Mpzf;
  LineKey key;
  key.axis = k;
  const M pk(coordinate(p, k)), qk(coordinate(q, k));
  M d = qk - pk;
  int slot = 0;
  for (int j = 0; j < 3; ++j) {
    if (j == k) continue;
    const M pj(coordinate(p, j)), qj(coordinate(q, j));
    key.num[slot] = qj - pj;                      // slope (q_j - p_j) / d
    key.num[slot + 2] = pj * qk - pk * qj;        // offset p_j - p_k slope = (p_j q_k - p_k q_j) / d
    ++slot;
  }
  if (d.sign() < 0) {
    d = M(0.0) - d;
    for (M& x : key.num) x = M(0.0) - x;
  }
  key.den = d;
  return key;
}

// -1, 0 or 1 as key a orders before, with or after b (one comparison: keys
// sorted are mostly equal, a line's edges together, and key_less both ways
// took every component twice).
int key_compare(const LineKey& a, const LineKey& b) {
  if (a.axis != b.axis) return a.axis < b.axis ? -1 : 1;
  for (int i = 0; i < 4; ++i)
    if (const int c = (a.num[i] * b.den - b.num[i] * a.den).sign()) return c;
  return 0;
}
bool key_less(const LineKey& a, const LineKey& b) { return key_compare(a, b) < 0; }

// Lines are first told apart without GMP. Each key value falls in a cell: the
// reals truncated (towards zero) to 1 + cell_bits significant bits. An edge
// whose key values, in doubles with their error bounds (or else in intervals),
// each lie inside one cell has its line's cells; one whose intervals straddle a
// border takes the cells of its exact key. Edges on one line thus always share their cells, and an edge alone in its cells (or
// sharing them only with edges between the same two vertices) is alone on its
// line: exact keys are needed only where cells are shared by other edges.
struct Cells {
  std::uint64_t mask;   // keeps the sign, the exponent and the leading mantissa bits
  explicit Cells(int bits) : mask(~((std::uint64_t(1) << (52 - std::clamp(bits, 0, 52))) - 1)) {}
  std::uint64_t of(double x) const {
    if (x == 0) return 0;   // (+0 and -0)
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b & mask;
  }
};

std::uint64_t mix(std::uint64_t h, std::uint64_t x) {
  h ^= x + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
  return h * 0xBF58476D1CE4E5B9ull;
}

std::uint64_t cells_of(const LineKey& key, const Cells& cells) {
  std::uint64_t h = mix(0, static_cast<std::uint64_t>(key.axis));
  const mpq_class den(key.den);
  for (const CGAL::Mpzf& n : key.num) {
    const mpq_class x = mpq_class(n) / den;
    h = mix(h, cells.of(x.get_d()));   // (get_d truncates)
  }
  return h;
}

// The cells of the line through p and q, from intervals (rounding upwards); false
// where an interval is not inside one cell of moderate magnitude. Where the
// doubles' bounds are in doubt: an operation that is exact gives a point
// interval (a slope of exactly 1 is on a border: its bound straddles it).
bool cells_from_intervals(const Vec3& p, const Vec3& q, int k, const Cells& cells, std::uint64_t& h) {
  using I = CGAL::Interval_nt<false>;
  const I pk(coordinate(p, k)), dk = I(coordinate(q, k)) - pk;
  std::array<I, 4> r;
  int slot = 0;
  for (int j = 0; j < 3; ++j) {
    if (j == k) continue;
    const I pj(coordinate(p, j)), slope = (I(coordinate(q, j)) - pj) / dk;
    r[slot] = slope;
    r[slot + 2] = pj - pk * slope;
    ++slot;
  }
  h = mix(0, static_cast<std::uint64_t>(k));
  for (const I& x : r) {
    const double lo = x.inf(), hi = x.sup();
    if (lo == 0 && hi == 0) { h = mix(h, 0); continue; }
    // Far from 1 (or not finite), leave it to GMP: mpq's get_d is then the judge.
    const double m = std::max(std::abs(lo), std::abs(hi));
    if (!(m < 0x1p900) || std::min(std::abs(lo), std::abs(hi)) < 0x1p-900) return false;
    const std::uint64_t c = cells.of(lo);
    if (c != cells.of(hi)) return false;
    h = mix(h, c);
  }
  return true;
}

// One key value's cell from its double v, rounded to nearest from the real
// value x with |v - x| <= err - u (|v| + err) (u = 2^-53): [v - err, v + err]
// rounded holds x, and a cell is an interval of the reals (the truncation is
// monotone). False where that interval meets two cells or leaves the moderate
// magnitudes (there, or where a bound could underflow, the exact key decides).
bool cell_within(double v, double err, const Cells& cells, std::uint64_t& c) {
  const double lo = std::abs(v - err), hi = std::abs(v + err);
  if (!(std::max(lo, hi) < 0x1p900) || std::min(lo, hi) < 0x1p-900) return false;
  c = cells.of(v - err);
  return c == cells.of(v + err);
}

// The cells of the line through p and q (k: the first axis along which they
// differ) from doubles rounded to nearest, each with an error bound; false
// where one value's cell is in doubt. Bounds (u = 2^-53, no underflow above
// 2^-900): the slope s = a / d is a quotient of two rounded differences,
// |s^ - s| <= 3.02u |s^|; the offset o = p_j - p_k s has |o^ - o| <=
// u (1.01 |o^| + 4.02 |p_k s^|) plus 2^-1075 where p_k s^ underflows. Each err
// below also covers rounding v -/+ err. An exact zero difference is exact.
bool cells_from_doubles(const Vec3& p, const Vec3& q, int k, const Cells& cells, std::uint64_t& h) {
  constexpr double u = 0x1p-53;
  const double pk = coordinate(p, k), dk = coordinate(q, k) - pk;
  std::array<std::uint64_t, 4> c;   // the slopes' cells, then the offsets'
  int slot = 0;
  for (int j = 0; j < 3; ++j) {
    if (j == k) continue;
    const double pj = coordinate(p, j), a = coordinate(q, j) - pj;
    if (a == 0) {   // (slope 0, offset p_j: both exact)
      c[slot] = 0;
      c[slot + 2] = cells.of(pj);
    } else {
      const double s = a / dk, t = pk * s, o = pj - t;
      if (!cell_within(s, 5 * u * std::abs(s), cells, c[slot]) ||
          !cell_within(o, 6 * u * (std::abs(o) + std::abs(t)) + 0x1p-1000, cells, c[slot + 2]))
        return false;
    }
    ++slot;
  }
  h = mix(0, static_cast<std::uint64_t>(k));
  for (std::uint64_t x : c) h = mix(h, x);
  return true;
}

// The cells of n lines, line(i) -> (p, q, k), into out[0 .. n): doubles first,
// then intervals for those in doubt, then exact keys (the rounding mode set
// once per stage, not per line).
template <class Line>
void cells_of_lines(std::size_t n, Line&& line, const Cells& cells, std::uint64_t* out) {
  std::vector<std::size_t> doubt;
  {
    CGAL::Protect_FPU_rounding<true> nearest(CGAL_FE_TONEAREST);   // (the doubles' bounds assume it)
    for (std::size_t i = 0; i < n; ++i) {
      const auto [p, q, k] = line(i);
      if (!cells_from_doubles(p, q, k, cells, out[i])) doubt.push_back(i);
    }
  }
  std::size_t inexact = 0;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    for (std::size_t i : doubt) {
      const auto [p, q, k] = line(i);
      if (!cells_from_intervals(p, q, k, cells, out[i])) doubt[inexact++] = i;
    }
  }
  for (std::size_t j = 0; j < inexact; ++j) {
    const auto [p, q, k] = line(doubt[j]);
    out[doubt[j]] = cells_of(line_key(p, q, k), cells);
  }
}

// Facet edges grouped by their (unordered) vertex pair: group g is
// edges[start[g] .. start[g+1]), in facet order; groups in order of (lower
// vertex, higher vertex). The edges are made straight into their places, so
// that every later pass reads a group's edges side by side.
struct EdgeGroups {
  std::vector<Edge> edges;
  std::vector<std::size_t> start;
};

// Facet f's edge i (p != q).
Edge edge_of(const WorldFacets& wf, int f, std::size_t i) {
  const auto& v = wf.facets[static_cast<std::size_t>(f)].v;
  return Edge{f, static_cast<std::uint32_t>(i), v[i], v[(i + 1) % v.size()]};
}

EdgeGroups group_by_vertex_pair(const Scene& scene, const WorldFacets& wf, int threads) {
  const std::size_t nvertices = scene.vertices.size();
  const int nf = static_cast<int>(wf.facets.size());
  std::size_t nedges = 0;
  for (const WorldFacet& f : wf.facets) nedges += f.v.size();
  // Counting sort by the lower vertex, stable: each part of the facets counts its
  // own edges; part k's edges of vertex v go after those of parts before k.
  const int parts = std::max(1, std::min<int>(threads, static_cast<int>(nedges / 65536)));
  auto part = [&](int k) { return static_cast<int>(static_cast<long>(nf) * k / parts); };
  auto vertices = [&](int k) { return nvertices * static_cast<std::size_t>(k) / static_cast<std::size_t>(parts); };
  auto each_lower = [&](int k, auto&& body) {
    for (int f = part(k); f < part(k + 1); ++f) {
      const auto& v = wf.facets[static_cast<std::size_t>(f)].v;
      for (std::size_t i = 0; i < v.size(); ++i) body(f, i, std::min(v[i], v[(i + 1) % v.size()]));
    }
  };
  std::vector<std::vector<std::uint32_t>> count(static_cast<std::size_t>(parts));
  parallel_for(parts, threads, [&](int k) {
    std::vector<std::uint32_t> c(nvertices, 0);
    each_lower(k, [&](int, std::size_t, std::uint32_t lo) { ++c[lo]; });
    count[static_cast<std::size_t>(k)] = std::move(c);
  });
  std::vector<std::uint32_t> first(nvertices + 1, 0);   // vertex v's edges: edges[first[v] .. first[v+1])
  for (std::size_t v = 0; v < nvertices; ++v) {
    std::uint32_t at = first[v];
    for (auto& c : count) {   // (c[v] becomes the part's next place)
      const std::uint32_t n = c[v];
      c[v] = at;
      at += n;
    }
    first[v + 1] = at;
  }
  EdgeGroups g;
  g.edges.resize(nedges);
  parallel_for(parts, threads, [&](int k) {
    std::vector<std::uint32_t>& next = count[static_cast<std::size_t>(k)];
    each_lower(k, [&](int f, std::size_t i, std::uint32_t lo) { g.edges[next[lo]++] = edge_of(wf, f, i); });
  });
  // Each vertex's edges by the higher vertex (stable), and where the groups start;
  // parts of the vertices in parallel.
  auto higher = [](const Edge& e) { return std::max(e.p, e.q); };
  std::vector<std::vector<std::size_t>> starts(static_cast<std::size_t>(parts));
  parallel_for(parts, threads, [&](int k) {
    std::vector<std::size_t> mine;
    for (std::size_t v = vertices(k); v < vertices(k + 1); ++v) {
      const auto b = g.edges.begin() + first[v], e = g.edges.begin() + first[v + 1];
      auto by_higher = [&](const Edge& x, const Edge& y) { return higher(x) < higher(y); };
      if (e - b <= 16) {   // (insertion sort: most vertices have a handful of edges)
        for (auto i = b; i != e; ++i)
          for (auto j = i; j != b && by_higher(*j, *(j - 1)); --j) std::iter_swap(j, j - 1);
      } else {
        std::stable_sort(b, e, by_higher);
      }
      for (auto i = b; i != e; ++i)
        if (i == b || higher(*i) != higher(*(i - 1))) mine.push_back(static_cast<std::size_t>(i - g.edges.begin()));
    }
    starts[static_cast<std::size_t>(k)] = std::move(mine);
  });
  std::size_t ngroups = 0;
  for (const auto& m : starts) ngroups += m.size();
  g.start.reserve(ngroups + 1);
  for (const auto& m : starts) g.start.insert(g.start.end(), m.begin(), m.end());
  g.start.push_back(nedges);
  return g;
}


// Sorts items [b, e) by their ranks (distinct), keeping each with its rank.
template <class Item, class Rank>
void sort_by_rank(std::vector<Item>& items, std::vector<Rank>& rank, std::size_t b, std::size_t e) {
  if (e - b <= 16) {   // (most facets: insertion sort)
    for (std::size_t i = b + 1; i < e; ++i)
      for (std::size_t j = i; j > b && rank[j] < rank[j - 1]; --j) {
        std::swap(rank[j], rank[j - 1]);
        std::swap(items[j], items[j - 1]);
      }
    return;
  }
  std::vector<std::size_t> by(e - b);
  for (std::size_t i = 0; i < by.size(); ++i) by[i] = b + i;
  std::sort(by.begin(), by.end(), [&](std::size_t x, std::size_t y) { return rank[x] < rank[y]; });
  std::vector<Item> moved;
  std::vector<Rank> ranks;
  moved.reserve(by.size());
  ranks.reserve(by.size());
  for (std::size_t i : by) {
    moved.push_back(std::move(items[i]));
    ranks.push_back(rank[i]);
  }
  std::move(moved.begin(), moved.end(), items.begin() + static_cast<std::ptrdiff_t>(b));
  std::copy(ranks.begin(), ranks.end(), rank.begin() + static_cast<std::ptrdiff_t>(b));
}

// Chunks of pieces, each with its ranks, in one vector in the order of each
// piece's first sharer (its facet), then by rank: the stages that read the
// pieces then walk the facets and vertices in order. Each piece's place, in one
// pass over the chunks; the pieces moved there in parallel. The chunks are emptied.
MatchedEdges in_facet_order(std::vector<MatchedEdges>& found, std::size_t nfacets, int threads) {
  const std::size_t nchunks = found.size();
  std::vector<std::uint32_t> next(nfacets + 1, 0);
  for (const MatchedEdges& f : found)
    for (const WorldPiece& p : f.pieces) ++next[p.sharers[0].facet + 1];
  for (std::size_t f = 0; f < nfacets; ++f) next[f + 1] += next[f];
  const std::vector<std::uint32_t> facet_start(next);
  std::vector<std::vector<std::uint32_t>> place(nchunks);
  for (std::size_t c = 0; c < nchunks; ++c)
    for (const WorldPiece& p : found[c].pieces) place[c].push_back(next[p.sharers[0].facet]++);
  MatchedEdges out;
  out.pieces.resize(next.back());
  out.rank.resize(next.back());
  parallel_for(static_cast<int>(nchunks), threads, [&](int c) {
    const auto k = static_cast<std::size_t>(c);
    for (std::size_t i = 0; i < found[k].pieces.size(); ++i) {
      out.pieces[place[k][i]] = std::move(found[k].pieces[i]);
      out.rank[place[k][i]] = found[k].rank[i];
    }
    MatchedEdges().pieces.swap(found[k].pieces);
  });
  parallel_chunks(static_cast<int>(nfacets), 4096, threads, [&](int, Chunk r) {
    for (auto f = static_cast<std::size_t>(r.begin); f < static_cast<std::size_t>(r.end); ++f)
      sort_by_rank(out.pieces, out.rank, facet_start[f], facet_start[f + 1]);
  });
  return out;
}

}  // namespace

MatchedEdges match_edges_ranked(const Scene& scene, const WorldFacets& wf, int cell_bits, int threads) {
  const Cells cells(cell_bits);
  auto vertex = [&](std::uint32_t id) -> const Vec3& { return scene.vertices[id]; };
  auto exact_key = [&](const Edge& e, int axis) {
    // Keyed from the lower vertex id so that both directions build the same numbers.
    const std::uint32_t lo = std::min(e.p, e.q), hi = std::max(e.p, e.q);
    return line_key(vertex(lo), vertex(hi), axis);
  };

  // Edges between the same two vertices (most edges of a mesh, twice each) are
  // one group: they lie on one line, so their line's cells are found once.
  // Counting sort by the lower vertex, then by the higher within it; stable, so a
  // group's edges stay in facet order.
  const EdgeGroups groups = group_by_vertex_pair(scene, wf, threads);
  const std::vector<Edge>& edges = groups.edges;
  const std::size_t ngroups = groups.start.size() - 1;
  auto group_edge = [&](std::size_t g) -> const Edge& { return edges[groups.start[g]]; };

  // Each group's line, from its lower vertex id to its higher (the exact key's
  // way), and the line's cells, in parallel.
  std::vector<LineDir> dir(ngroups);
  std::vector<std::uint64_t> cells_at(ngroups);
  auto lower = [&](std::size_t g) -> const Vec3& { return vertex(std::min(group_edge(g).p, group_edge(g).q)); };
  auto higher = [&](std::size_t g) -> const Vec3& { return vertex(std::max(group_edge(g).p, group_edge(g).q)); };
  parallel_chunks(static_cast<int>(ngroups), 8192, threads, [&](int, Chunk r) {
    for (auto g = static_cast<std::size_t>(r.begin); g < static_cast<std::size_t>(r.end); ++g)
      dir[g] = line_dir(lower(g), higher(g));
    auto line = [&](std::size_t i) {
      const std::size_t g = static_cast<std::size_t>(r.begin) + i;
      return std::tuple<const Vec3&, const Vec3&, int>(lower(g), higher(g), dir[g].axis);
    };
    cells_of_lines(static_cast<std::size_t>(r.end - r.begin), line, cells, cells_at.data() + r.begin);
  });
  // Whether edge e (of group g) runs up its line's axis.
  auto forward = [&](const Edge& e, std::size_t g) { return (e.p < e.q) == dir[g].up; };
  // Groups sorted by (cells, vertex pair): a run of several groups with equal
  // cells is a candidate line, handled once, by its first group.
  struct Slot {
    std::uint64_t hash;
    std::uint32_t group;   // (groups are numbered in vertex-pair order)
  };
  // (The hashes are mixed, so their top bits spread them evenly: a counting
  // sort by the top 16 bits, in group order (its parts side by side), leaves
  // buckets of a few dozen to sort, in parallel; the same order as one
  // comparison sort, at a third of its cost.)
  std::vector<Slot> slots(ngroups);
  {
    constexpr int shift = 48;
    const Buckets by_top = bucket_items(static_cast<int>(ngroups), std::size_t{1} << (64 - shift), threads,
                                        [&](int g, auto&& in) { in(cells_at[static_cast<std::size_t>(g)] >> shift); });
    const std::vector<std::uint32_t>& bucket_start = by_top.first;
    parallel_chunks(static_cast<int>(ngroups), 65536, threads, [&](int, Chunk r) {
      for (auto k = static_cast<std::size_t>(r.begin); k < static_cast<std::size_t>(r.end); ++k)
        slots[k] = Slot{cells_at[by_top.items[k]], by_top.items[k]};
    });
    const int nbuckets = static_cast<int>(bucket_start.size() - 1);
    parallel_chunks(nbuckets, 1024, threads, [&](int, Chunk r) {
      for (int b = r.begin; b < r.end; ++b)
        std::sort(slots.begin() + bucket_start[static_cast<std::size_t>(b)],
                  slots.begin() + bucket_start[static_cast<std::size_t>(b) + 1], [](const Slot& x, const Slot& y) {
                    return x.hash != y.hash ? x.hash < y.hash : x.group < y.group;   // (a total order)
                  });
    });
  }
  constexpr std::uint32_t alone = UINT32_MAX, in_run = UINT32_MAX - 1;
  std::vector<std::uint32_t> run_at(ngroups, alone);   // a run's first group: where its slots start
  for (std::size_t lo = 0; lo < ngroups;) {
    std::size_t hi = lo + 1;
    while (hi < ngroups && slots[hi].hash == slots[lo].hash) ++hi;
    if (hi > lo + 1) {
      run_at[slots[lo].group] = static_cast<std::uint32_t>(lo);
      for (std::size_t s = lo + 1; s < hi; ++s) run_at[slots[s].group] = in_run;
    }
    lo = hi;
  }

  auto sharer = [](const Edge& e, bool up_its_line) { return Sharer{e.facet, e.edge, up_its_line}; };
  auto by_facet = [](const Sharer& x, const Sharer& y) {
    return x.facet < y.facet || (x.facet == y.facet && x.edge < y.edge);
  };

  // Edges of one exact line: sweep along its axis k; each elementary interval
  // covered by at least one edge is a piece shared by all edges covering it.
  struct Event {
    double t;
    std::uint32_t vertex;
    std::uint32_t edge;
    bool start;
  };
  struct Scratch {
    std::vector<Event> events;
    std::vector<std::uint32_t> active, group;
    std::vector<std::pair<LineKey, std::uint32_t>> keyed;
  };
  auto sweep_line = [&](const std::uint32_t* line, std::size_t n, int k, Scratch& w, std::vector<WorldPiece>& pieces) {
    std::vector<Event>& events = w.events;
    std::vector<std::uint32_t>& active = w.active;
    events.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const Edge& e = edges[line[i]];
      const double tp = coordinate(vertex(e.p), k), tq = coordinate(vertex(e.q), k);
      const bool fwd = tp < tq;
      events.push_back({fwd ? tp : tq, fwd ? e.p : e.q, line[i], true});
      events.push_back({fwd ? tq : tp, fwd ? e.q : e.p, line[i], false});
    }
    std::sort(events.begin(), events.end(), [](const Event& x, const Event& y) {
      return x.t < y.t || (x.t == y.t && x.start < y.start);
    });
    active.clear();
    for (std::size_t i = 0; i < events.size();) {
      std::size_t j = i;
      const std::uint32_t here = events[i].vertex;
      for (; j < events.size() && events[j].t == events[i].t; ++j) {
        if (events[j].start) active.push_back(events[j].edge);
        else active.erase(std::find(active.begin(), active.end(), events[j].edge));
      }
      if (!active.empty() && j < events.size()) {
        WorldPiece piece{here, events[j].vertex, {}};
        for (auto ei : active) {
          const Edge& e = edges[ei];
          piece.sharers.push_back(sharer(e, coordinate(vertex(e.p), k) < coordinate(vertex(e.q), k)));
        }
        std::sort(piece.sharers.begin(), piece.sharers.end(), by_facet);
        pieces.push_back(std::move(piece));
      }
      i = j;
    }
  };

  // Where a piece goes among those of its first sharer (PieceRank): by its
  // line's cells, then its place in the run's sweeps (the order of one pass over the runs).
  using Rank = PieceRank;
  using Found = MatchedEdges;
  // A group alone in its cells is one piece (its edges, any number, lie between
  // the same two vertices; the first is its first sharer: they are in facet order).
  auto alone_piece = [&](std::size_t g) {
    const Edge& e = group_edge(g);
    WorldPiece piece{forward(e, g) ? e.p : e.q, forward(e, g) ? e.q : e.p, {}};
    for (std::size_t i = groups.start[g]; i < groups.start[g + 1]; ++i)
      piece.sharers.push_back(sharer(edges[i], forward(edges[i], g)));
    return piece;
  };
  // A run's first group makes the pieces of every group of the run, told apart
  // by exact keys.
  // (One exact key per group, not per edge: its edges lie between the same two
  // vertices. Groups sorted by (key, group) list their edges as the edges sorted
  // by (key, edge) would: a group's edges are consecutive, groups in order.)
  auto pieces_of_run = [&](std::size_t g, Scratch& w, Found& out) {
    auto& keyed = w.keyed;   // (key, group)
    keyed.clear();
    const std::size_t lo = run_at[g];
    for (std::size_t s = lo; s < ngroups && slots[s].hash == slots[lo].hash; ++s) {
      const std::uint32_t h = slots[s].group;
      keyed.emplace_back(exact_key(group_edge(h), dir[h].axis), h);
    }
    std::sort(keyed.begin(), keyed.end(), [](const auto& x, const auto& y) {
      const int c = key_compare(x.first, y.first);
      return c != 0 ? c < 0 : x.second < y.second;
    });
    const std::size_t first = out.pieces.size();
    for (std::size_t a = 0; a < keyed.size();) {
      std::size_t b = a + 1;
      while (b < keyed.size() && !key_less(keyed[a].first, keyed[b].first)) ++b;
      w.group.clear();
      for (std::size_t i = a; i < b; ++i)
        for (std::size_t e = groups.start[keyed[i].second]; e < groups.start[keyed[i].second + 1]; ++e)
          w.group.push_back(static_cast<std::uint32_t>(e));
      sweep_line(w.group.data(), w.group.size(), keyed[a].first.axis, w, out.pieces);
      a = b;
    }
    for (std::size_t i = first; i < out.pieces.size(); ++i)
      out.rank.push_back(Rank{cells_at[g], static_cast<std::uint32_t>(i - first)});
  };
  // The runs' pieces, chunks of groups in parallel (runs are rare: lines that
  // several vertex pairs share).
  const std::size_t nchunks = std::clamp<std::size_t>(ngroups / 8192, 1, 256);
  auto chunk_of = [&](std::size_t k) { return std::pair(ngroups * k / nchunks, ngroups * (k + 1) / nchunks); };
  std::vector<Found> runs(nchunks);
  parallel_for(static_cast<int>(nchunks), threads, [&](int c) {
    Scratch w;
    Found mine;   // (filled here, stored once: the chunks' slots share cache lines)
    const auto [from, to] = chunk_of(static_cast<std::size_t>(c));
    for (std::size_t g = from; g < to; ++g)
      if (run_at[g] != alone && run_at[g] != in_run) pieces_of_run(g, w, mine);
    runs[static_cast<std::size_t>(c)] = std::move(mine);
  });
  // Every piece straight to its place among its first sharer's (facet order,
  // then rank): each facet's pieces counted, then placed by a counter per facet
  // in whatever order the threads come, then sorted by their ranks (distinct).
  const std::size_t nfacets = wf.facets.size();
  std::vector<std::uint32_t> next(nfacets + 1, 0);
  auto take = [&](int facet) { return shared_fetch_add(next[static_cast<std::size_t>(facet)], 1u, threads); };
  parallel_for(static_cast<int>(nchunks), threads, [&](int c) {
    const auto [from, to] = chunk_of(static_cast<std::size_t>(c));
    for (std::size_t g = from; g < to; ++g)
      if (run_at[g] == alone) take(group_edge(g).facet + 1);
    for (const WorldPiece& p : runs[static_cast<std::size_t>(c)].pieces) take(p.sharers[0].facet + 1);
  });
  for (std::size_t f = 0; f < nfacets; ++f) next[f + 1] += next[f];
  const std::vector<std::uint32_t> facet_start(next);
  Found out;
  out.pieces.resize(next.back());
  out.rank.resize(next.back());
  parallel_for(static_cast<int>(nchunks), threads, [&](int c) {
    const std::pair<std::size_t, std::size_t> range = chunk_of(static_cast<std::size_t>(c));
    const std::size_t from = range.first, to = range.second;   // (named: the lambda below reads them)
    // (Each group's place is taken kAhead groups before its piece is written
    // there, and fetched meanwhile: the places scatter over all the pieces, a
    // cache miss each. The places are taken in the same order.)
    constexpr std::size_t kAhead = 16;
    std::array<std::uint32_t, kAhead> place{};   // group g's at g % kAhead
    auto take_place = [&](std::size_t g) {
      if (g >= to || run_at[g] != alone) return;
      const std::uint32_t at = place[g % kAhead] = take(group_edge(g).facet);
      __builtin_prefetch(&out.pieces[at], 1);
      __builtin_prefetch(&out.rank[at], 1);
    };
    for (std::size_t g = from; g < from + kAhead; ++g) take_place(g);
    for (std::size_t g = from; g < to; ++g) {
      if (run_at[g] == alone) {
        const std::uint32_t at = place[g % kAhead];
        out.pieces[at] = alone_piece(g);
        out.rank[at] = Rank{cells_at[g], 0};
      }
      take_place(g + kAhead);
    }
    Found& mine = runs[static_cast<std::size_t>(c)];
    for (std::size_t i = 0; i < mine.pieces.size(); ++i) {
      const std::uint32_t at = take(mine.pieces[i].sharers[0].facet);
      out.pieces[at] = std::move(mine.pieces[i]);
      out.rank[at] = mine.rank[i];
    }
  });
  parallel_chunks(static_cast<int>(nfacets), 4096, threads, [&](int, Chunk r) {
    for (auto f = static_cast<std::size_t>(r.begin); f < static_cast<std::size_t>(r.end); ++f)
      sort_by_rank(out.pieces, out.rank, facet_start[f], facet_start[f + 1]);
  });
  return out;
}

std::optional<std::vector<WorldPiece>> pieces_of_vertex_pairs(const Scene& scene, const WorldFacets& wf,
                                                               const std::vector<std::uint32_t>& local,
                                                               std::size_t nused, int threads) {
  const std::size_t nf = wf.facets.size();
  if (nf == 0 || nf >= (std::size_t{1} << 28)) return std::nullopt;   // (3 nf fits in 30 bits)
  // (A disk's pairs E of which B are one edge's: 3 F = 2 E - B, and V - E + F = 1,
  // so B = 2 V - F - 2, and a height field's boundary has 3 pieces or more. A
  // closed surface, B = 0, leaves here before any pair is made: 2 V - F <= 4.)
  if (2 * nused < nf + 5) return std::nullopt;
  for (const WorldFacet& f : wf.facets)
    if (f.v.size() != 3) return std::nullopt;
  // Facet edge e = 3 f + i: the numbers of its ends, from v[i] to v[i + 1].
  auto ends = [&](std::size_t e) {
    const auto& v = wf.facets[e / 3].v;
    const std::size_t i = e % 3;
    return std::pair{local[v[i]], local[v[(i + 1) % 3]]};
  };
  const auto nedges = static_cast<int>(3 * nf);
  // Each facet edge under the lower of its ends' numbers (stable: in facet
  // order), as its higher end's number, its place e and whether it runs from
  // the lower end.
  struct Half {
    std::uint32_t hi;
    std::uint32_t at : 31;
    std::uint32_t from_lo : 1;
  };
  std::vector<Half> half;   // lower end v's halves: half[first[v] .. first[v + 1])
  const std::vector<std::uint32_t> first = counted_placement(
      nedges, nused, threads,
      [&](int e, auto&& visit) {
        const auto [p, q] = ends(static_cast<std::size_t>(e));
        visit(std::min(p, q));
      },
      [&](std::uint32_t total) { half.resize(total); },
      [&](int e, std::uint32_t slot) {
        const auto [p, q] = ends(static_cast<std::size_t>(e));
        half[slot] = Half{std::max(p, q), static_cast<std::uint32_t>(e), p < q};
      });
  // Each lower end's halves by their higher end (stable: a pair's in facet
  // order, side by side). Per facet edge, where its pair's halves start, with
  // whether it is the first of them and whether there are two. (Chunks of
  // lower ends side by side: each writes its own halves' places.)
  constexpr std::uint32_t kTwo = 1u << 31, kFirst = 1u << 30, kStart = kFirst - 1;
  std::vector<std::uint32_t> pair_at(static_cast<std::size_t>(nedges));
  const int vsize = 16384, vchunks = chunk_count(static_cast<int>(nused), vsize);
  std::vector<char> three(static_cast<std::size_t>(vchunks), 0);
  parallel_chunks(static_cast<int>(nused), vsize, threads, [&](int c, Chunk r) {
    for (auto v = static_cast<std::size_t>(r.begin); v < static_cast<std::size_t>(r.end); ++v) {
      const std::uint32_t b = first[v], e = first[v + 1];
      for (std::uint32_t i = b + 1; i < e; ++i)
        for (std::uint32_t j = i; j > b && half[j].hi < half[j - 1].hi; --j) std::swap(half[j], half[j - 1]);
      for (std::uint32_t i = b; i < e;) {
        std::uint32_t j = i + 1;
        while (j < e && half[j].hi == half[i].hi) ++j;
        if (j - i > 2) {   // (three facets on one edge: no disk)
          three[static_cast<std::size_t>(c)] = 1;
          return;
        }
        for (std::uint32_t k = i; k < j; ++k) pair_at[half[k].at] = i | (j - i == 2 ? kTwo : 0) | (k == i ? kFirst : 0);
        i = j;
      }
    }
  });
  if (std::find(three.begin(), three.end(), 1) != three.end()) return std::nullopt;
  // Facet by facet, the pieces whose first facet edge it holds, by their
  // vertex pairs (their ranks: vertex_pair_ranks): chunks of facets side by
  // side, each chunk's pieces (its edges that are their pair's first) after
  // those of the chunks before; all of them are the pairs.
  const int fsize = 16384, fchunks = chunk_count(static_cast<int>(nf), fsize);
  std::vector<std::size_t> start(static_cast<std::size_t>(fchunks) + 1, 0);
  parallel_chunks(static_cast<int>(nf), fsize, threads, [&](int c, Chunk r) {
    start[static_cast<std::size_t>(c) + 1] = static_cast<std::size_t>(
        std::count_if(pair_at.begin() + 3 * r.begin, pair_at.begin() + 3 * r.end, [](std::uint32_t x) { return (x & kFirst) != 0; }));
  });
  for (std::size_t c = 0; c < static_cast<std::size_t>(fchunks); ++c) start[c + 1] += start[c];
  const std::size_t npairs = start.back();
  if (nused + nf != npairs + 1) return std::nullopt;   // (V - E + F != 1)
  std::vector<WorldPiece> pieces;
  pieces.reserve(npairs);
  fault_in_spare(pieces, npairs, threads);
  pieces.resize(npairs);
  parallel_chunks(static_cast<int>(nf), fsize, threads, [&](int c, Chunk r) {
    std::size_t next = start[static_cast<std::size_t>(c)];
    for (auto f = static_cast<std::size_t>(r.begin); f < static_cast<std::size_t>(r.end); ++f) {
      const auto& v = wf.facets[f].v;
      std::array<std::uint32_t, 3> mine{};
      std::size_t k = 0;
      for (std::uint32_t i = 0; i < 3; ++i)
        if (pair_at[3 * f + i] & kFirst) mine[k++] = i;
      auto pair_of = [&](std::uint32_t i) { return std::minmax(v[i], v[(i + 1) % 3]); };
      for (std::size_t x = 1; x < k; ++x)   // (at most three)
        for (std::size_t y = x; y > 0 && pair_of(mine[y]) < pair_of(mine[y - 1]); --y) std::swap(mine[y], mine[y - 1]);
      for (std::size_t m = 0; m < k; ++m) {
        const std::uint32_t i = mine[m], at = static_cast<std::uint32_t>(3 * f) + i, s = pair_at[at] & kStart;
        // (From its lower end to its higher in (x, y, z) order, as match_edges
        // runs a piece: up the first axis along which its ends differ.)
        const std::uint32_t p = v[i], q = v[(i + 1) % 3];
        const bool up = line_dir(scene.vertices[p], scene.vertices[q]).up;
        WorldPiece& piece = pieces[next++];
        piece = WorldPiece{up ? p : q, up ? q : p, {}};
        piece.sharers.push_back(Sharer{static_cast<int>(f), i, up});
        if (pair_at[at] & kTwo) {
          const Half& other = half[s + 1];
          const bool same_way = other.from_lo == half[s].from_lo;
          piece.sharers.push_back(Sharer{static_cast<int>(other.at / 3), static_cast<std::uint32_t>(other.at % 3),
                                         same_way == up});
        }
      }
    }
  });
  return pieces;
}

std::vector<PieceRank> vertex_pair_ranks(const std::vector<WorldPiece>& pieces) {
  std::vector<PieceRank> rank(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto [lo, hi] = std::minmax(pieces[i].a, pieces[i].b);
    rank[i] = PieceRank{std::uint64_t{lo} << 32 | hi, 0};
  }
  return rank;
}

std::uint64_t line_cells(const Vec3& p, const Vec3& q, int cell_bits, bool exact_only) {
  const Cells cells(cell_bits);
  const int k = p.x != q.x ? 0 : p.y != q.y ? 1 : 2;
  if (exact_only) return cells_of(line_key(p, q, k), cells);
  std::uint64_t h;
  cells_of_lines(1, [&](std::size_t) { return std::tuple<const Vec3&, const Vec3&, int>(p, q, k); }, cells, &h);
  return h;
}

std::vector<WorldPiece> match_edges(const Scene& scene, const WorldFacets& wf, int cell_bits, int threads) {
  return match_edges_ranked(scene, wf, cell_bits, threads).pieces;
}

MatchedEdges renumber_facets(const MatchedEdges& m, const std::vector<std::uint32_t>& new_index, int threads) {
  // Chunks of pieces renumbered in parallel, each piece's sharers in the order
  // of their new numbers (as matching would list them), then all put in order.
  const int n = static_cast<int>(m.pieces.size()), size = 16384;
  std::vector<MatchedEdges> chunks(static_cast<std::size_t>(std::max(1, chunk_count(n, size))));
  parallel_chunks(n, size, threads, [&](int k, Chunk r) {
    MatchedEdges mine;   // (filled here, stored once)
    mine.pieces.reserve(static_cast<std::size_t>(r.end - r.begin));
    mine.rank.assign(m.rank.begin() + r.begin, m.rank.begin() + r.end);
    for (int i = r.begin; i < r.end; ++i) {
      WorldPiece p = m.pieces[static_cast<std::size_t>(i)];
      for (Sharer& s : p.sharers) s.facet = static_cast<int>(new_index[static_cast<std::size_t>(s.facet)]);
      std::sort(p.sharers.begin(), p.sharers.end(), [](const Sharer& x, const Sharer& y) {
        return x.facet < y.facet || (x.facet == y.facet && x.edge < y.edge);
      });
      mine.pieces.push_back(std::move(p));
    }
    chunks[static_cast<std::size_t>(k)] = std::move(mine);
  });
  return in_facet_order(chunks, new_index.size(), threads);
}

}  // namespace vismap::engine
