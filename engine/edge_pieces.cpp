#include "engine/edge_pieces.h"

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <functional>

namespace vismap::engine {
namespace {

struct Edge {
  int facet;
  std::uint8_t edge;
  std::uint32_t p, q;   // vertex ids, facet order
};

// The supporting line of p->q as an exact canonical key: the first axis k along
// which the line moves, the slopes d_j/d_k and the offsets at x_k = 0.
struct LineKey {
  int axis = 0;
  std::array<mpq_class, 4> r;
  std::size_t hash = 0;
};

double coord(const Vec3& v, int k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; }

LineKey line_key(const Vec3& p, const Vec3& q) {
  LineKey key;
  while (coord(p, key.axis) == coord(q, key.axis)) ++key.axis;   // p != q
  const int k = key.axis;
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
  std::size_t h = std::hash<int>()(k);
  for (auto& x : key.r) h = h * 0x9E3779B97F4A7C15ull ^ std::hash<double>()(x.get_d() + 0.0);
  key.hash = h;
  return key;
}

bool same_line(const LineKey& a, const LineKey& b) {
  return a.axis == b.axis && a.r == b.r;
}
bool key_less(const LineKey& a, const LineKey& b) {
  if (a.hash != b.hash) return a.hash < b.hash;
  if (a.axis != b.axis) return a.axis < b.axis;
  for (int i = 0; i < 4; ++i) {
    int c = cmp(a.r[i], b.r[i]);
    if (c) return c < 0;
  }
  return false;
}

}  // namespace

std::vector<WorldPiece> match_edges(const Scene& scene, const WorldFacets& wf) {
  std::vector<Edge> edges;
  for (int f = 0; f < static_cast<int>(wf.facets.size()); ++f) {
    const auto& v = wf.facets[f].v;
    for (std::size_t i = 0; i < v.size(); ++i)
      edges.push_back(Edge{f, static_cast<std::uint8_t>(i), v[i], v[(i + 1) % v.size()]});
  }
  std::vector<LineKey> keys(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e)
    keys[e] = line_key(scene.vertices[edges[e].p], scene.vertices[edges[e].q]);
  std::vector<std::uint32_t> order(edges.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto x, auto y) {
    if (key_less(keys[x], keys[y])) return true;
    if (key_less(keys[y], keys[x])) return false;
    return x < y;
  });

  std::vector<WorldPiece> pieces;
  pieces.reserve(edges.size() * 3 / 5);
  struct Event {
    double t;
    std::uint32_t vertex;
    std::uint32_t edge;
    bool start;
  };
  std::vector<Event> events;
  std::vector<std::uint32_t> active;
  for (std::size_t lo = 0; lo < order.size();) {
    std::size_t hi = lo + 1;
    while (hi < order.size() && same_line(keys[order[lo]], keys[order[hi]])) ++hi;
    const int k = keys[order[lo]].axis;
    // Sweep the edges of this line along axis k; each elementary interval covered
    // by at least one edge is a piece shared by all edges covering it.
    events.clear();
    for (std::size_t i = lo; i < hi; ++i) {
      const Edge& e = edges[order[i]];
      double tp = coord(scene.vertices[e.p], k), tq = coord(scene.vertices[e.q], k);
      bool fwd = tp < tq;
      events.push_back({fwd ? tp : tq, fwd ? e.p : e.q, order[i], true});
      events.push_back({fwd ? tq : tp, fwd ? e.q : e.p, order[i], false});
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
          piece.sharers.push_back(Sharer{e.facet, e.edge, coord(scene.vertices[e.p], k) < coord(scene.vertices[e.q], k)});
        }
        std::sort(piece.sharers.begin(), piece.sharers.end(),
                  [](const Sharer& x, const Sharer& y) { return x.facet < y.facet || (x.facet == y.facet && x.edge < y.edge); });
        pieces.push_back(std::move(piece));
      }
      i = j;
    }
    lo = hi;
  }
  return pieces;
}

}  // namespace vismap::engine
