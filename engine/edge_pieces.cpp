#include "engine/edge_pieces.h"

#include <CGAL/Interval_nt.h>
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "engine/parallel.h"

namespace vismap::engine {
namespace {

struct Edge {
  int facet;
  std::uint32_t edge;   // a convex planar polygon is one facet of up to 10^6 corners
  std::uint8_t axis;    // the first axis along which the edge moves
  bool forward;         // p -> q runs that axis upwards
  std::uint32_t p, q;   // vertex ids, facet order
};

double coord(const Vec3& v, int k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; }

// The supporting line of p->q as an exact canonical key: the first axis k along
// which the line moves, the slopes d_j/d_k and the offsets at x_k = 0.
struct LineKey {
  int axis = 0;
  std::array<mpq_class, 4> r;
};

LineKey line_key(const Vec3& p, const Vec3& q, int k) {
  LineKey key;
  key.axis = k;
  mpq_class pk(coord(p, k)), dk = mpq_class(coord(q, k)) - pk;
  int slot = 0;
  for (int j = 0; j < 3; ++j) {
    if (j == k) continue;
    mpq_class pj(coord(p, j));
    mpq_class slope = (mpq_class(coord(q, j)) - pj) / dk;
    key.r[slot] = slope;
    key.r[slot + 2] = pj - pk * slope;
    ++slot;
  }
  return key;
}

bool key_less(const LineKey& a, const LineKey& b) {
  if (a.axis != b.axis) return a.axis < b.axis;
  for (int i = 0; i < 4; ++i) {
    int c = cmp(a.r[i], b.r[i]);
    if (c) return c < 0;
  }
  return false;
}

// Lines are first told apart without GMP. Each key value falls in a cell: the
// reals truncated (towards zero) to 1 + cell_bits significant bits. An edge whose key
// values' intervals each lie inside one cell has its line's cells; one whose
// intervals straddle a border takes the cells of its exact key. Edges on one
// line thus always share their cells, and an edge alone in its cells (or
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
  for (const mpq_class& x : key.r) h = mix(h, cells.of(x.get_d()));   // (get_d truncates)
  return h;
}

// The cells of the line through p and q, from intervals; false where an
// interval is not inside one cell of moderate magnitude.
bool cells_from_intervals(const Vec3& p, const Vec3& q, int k, const Cells& cells, std::uint64_t& h) {
  using I = CGAL::Interval_nt<false>;
  const I pk(coord(p, k)), dk = I(coord(q, k)) - pk;
  std::array<I, 4> r;
  int slot = 0;
  for (int j = 0; j < 3; ++j) {
    if (j == k) continue;
    const I pj(coord(p, j)), slope = (I(coord(q, j)) - pj) / dk;
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

}  // namespace

std::vector<WorldPiece> match_edges(const Scene& scene, const WorldFacets& wf, int cell_bits, int threads) {
  const Cells cells(cell_bits);
  // Every facet edge, in facet order (chunks of facets in parallel, each edge
  // in its slot: start[f] is facet f's first).
  const int nf = static_cast<int>(wf.facets.size());
  std::vector<std::size_t> start(static_cast<std::size_t>(nf) + 1, 0);
  for (int f = 0; f < nf; ++f) start[f + 1] = start[f] + wf.facets[f].v.size();
  std::vector<Edge> edges(start[nf]);
  parallel_chunks(nf, 4096, threads, [&](int, Chunk r) {
    for (int f = r.begin; f < r.end; ++f) {
      const auto& v = wf.facets[f].v;
      for (std::size_t i = 0; i < v.size(); ++i) {
        const std::uint32_t p = v[i], q = v[(i + 1) % v.size()];
        const Vec3 &a = scene.vertices[p], &b = scene.vertices[q];
        const std::uint8_t axis = a.x != b.x ? 0 : a.y != b.y ? 1 : 2;   // (p != q)
        edges[start[f] + i] = Edge{f, static_cast<std::uint32_t>(i), axis, coord(a, axis) < coord(b, axis), p, q};
      }
    }
  });
  auto vertex = [&](std::uint32_t id) -> const Vec3& { return scene.vertices[id]; };
  auto exact_key = [&](const Edge& e) {
    // Keyed from the lower vertex id so that both directions build the same numbers.
    const std::uint32_t lo = std::min(e.p, e.q), hi = std::max(e.p, e.q);
    return line_key(vertex(lo), vertex(hi), e.axis);
  };

  // Sort by (cells, vertex pair): runs of equal cells are candidate lines. Each
  // slot carries its edge, so the runs are read in order.
  struct Slot {
    std::uint64_t hash, pair;
    std::uint32_t edge;
    Edge e;
  };
  // Each edge's line cells, in parallel (chunks of edges, each slot its own).
  std::vector<Slot> slots(edges.size());
  parallel_chunks(static_cast<int>(edges.size()), 8192, threads, [&](int, Chunk r) {
    CGAL::Protect_FPU_rounding<true> upward;
    for (auto i = static_cast<std::uint32_t>(r.begin); i < static_cast<std::uint32_t>(r.end); ++i) {
      const Edge& e = edges[i];
      const std::uint32_t lo = std::min(e.p, e.q), hi = std::max(e.p, e.q);
      std::uint64_t h;
      if (!cells_from_intervals(vertex(lo), vertex(hi), e.axis, cells, h)) {
        CGAL::Protect_FPU_rounding<false> nearest;
        h = cells_of(exact_key(e), cells);
      }
      slots[i] = Slot{h, std::uint64_t(lo) << 32 | hi, i, e};
    }
  });
  engine::parallel_sort(slots.begin(), slots.end(), [](const Slot& x, const Slot& y) {
    if (x.hash != y.hash) return x.hash < y.hash;
    if (x.pair != y.pair) return x.pair < y.pair;
    return x.edge < y.edge;   // (a total order: the same for every thread count)
  }, threads);

  auto sharer = [](const Edge& e) { return Sharer{e.facet, e.edge, e.forward}; };
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
  auto sweep_line = [&](const std::uint32_t* line, std::size_t n, Scratch& w, std::vector<WorldPiece>& pieces) {
    const int k = edges[line[0]].axis;
    std::vector<Event>& events = w.events;
    std::vector<std::uint32_t>& active = w.active;
    events.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const Edge& e = edges[line[i]];
      const double tp = coord(vertex(e.p), k), tq = coord(vertex(e.q), k);
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
        for (auto ei : active) piece.sharers.push_back(sharer(edges[ei]));
        std::sort(piece.sharers.begin(), piece.sharers.end(), by_facet);
        pieces.push_back(std::move(piece));
      }
      i = j;
    }
  };

  // The pieces of the runs of equal cells that start in slots [from, to).
  auto pieces_of_runs = [&](std::size_t from, std::size_t to, Scratch& w, std::vector<WorldPiece>& pieces) {
    for (std::size_t lo = from; lo < to;) {
      std::size_t hi = lo + 1;
      bool one_pair = true;
      for (; hi < slots.size() && slots[hi].hash == slots[lo].hash; ++hi) one_pair &= slots[hi].pair == slots[lo].pair;
      if (one_pair) {
        // Alone on its line (with any edges between the same two vertices): one piece.
        const Edge& e = slots[lo].e;
        WorldPiece piece{e.forward ? e.p : e.q, e.forward ? e.q : e.p, {}};
        for (std::size_t i = lo; i < hi; ++i) piece.sharers.push_back(sharer(slots[i].e));
        std::sort(piece.sharers.begin(), piece.sharers.end(), by_facet);
        pieces.push_back(std::move(piece));
      } else {
        // Several vertex pairs share the cells: told apart by exact keys.
        auto& keyed = w.keyed;
        keyed.clear();
        for (std::size_t i = lo; i < hi; ++i) keyed.emplace_back(exact_key(slots[i].e), slots[i].edge);
        std::sort(keyed.begin(), keyed.end(), [](const auto& x, const auto& y) {
          if (key_less(x.first, y.first)) return true;
          if (key_less(y.first, x.first)) return false;
          return x.second < y.second;
        });
        for (std::size_t a = 0; a < keyed.size();) {
          std::size_t b = a + 1;
          while (b < keyed.size() && !key_less(keyed[a].first, keyed[b].first)) ++b;
          w.group.clear();
          for (std::size_t i = a; i < b; ++i) w.group.push_back(keyed[i].second);
          sweep_line(w.group.data(), w.group.size(), w, pieces);
          a = b;
        }
      }
      lo = hi;
    }
  };
  // Chunks of slots cut where a run starts, in parallel; their pieces joined in
  // chunk order are those of one pass over the runs in order.
  const std::size_t nslots = slots.size(), nchunks = std::clamp<std::size_t>(nslots / 16384, 1, 256);
  std::vector<std::size_t> cut(nchunks + 1, nslots);
  for (std::size_t c = 0; c < nchunks; ++c) {
    std::size_t at = nslots * c / nchunks;
    while (at > 0 && at < nslots && slots[at].hash == slots[at - 1].hash) ++at;
    cut[c] = at;
  }
  std::vector<std::vector<WorldPiece>> found(nchunks);
  parallel_for(static_cast<int>(nchunks), threads, [&](int c) {
    Scratch w;
    const auto k = static_cast<std::size_t>(c);
    std::vector<WorldPiece> mine;   // (filled here, stored once: the chunks' slots share cache lines)
    mine.reserve((cut[k + 1] - cut[k]) * 3 / 5);
    pieces_of_runs(cut[k], cut[k + 1], w, mine);
    found[k] = std::move(mine);
  });
  // In facet order (of each piece's first sharer; stable): the stages that read
  // the pieces then walk the facets and vertices in order. Each piece's place,
  // in one pass over the chunks in order; the pieces moved there in parallel.
  std::vector<std::uint32_t> next(wf.facets.size() + 1, 0);
  for (const auto& f : found)
    for (const WorldPiece& p : f) ++next[p.sharers[0].facet + 1];
  for (std::size_t f = 0; f < wf.facets.size(); ++f) next[f + 1] += next[f];
  std::vector<std::vector<std::uint32_t>> place(nchunks);
  for (std::size_t c = 0; c < nchunks; ++c)
    for (const WorldPiece& p : found[c]) place[c].push_back(next[p.sharers[0].facet]++);
  std::vector<WorldPiece> ordered(next.back());
  parallel_for(static_cast<int>(nchunks), threads, [&](int c) {
    const auto k = static_cast<std::size_t>(c);
    for (std::size_t i = 0; i < found[k].size(); ++i) ordered[place[k][i]] = std::move(found[k][i]);
    std::vector<WorldPiece>().swap(found[k]);
  });
  return ordered;
}

}  // namespace vismap::engine
