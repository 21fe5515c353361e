#include "engine/culling.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <optional>

#include "engine/parallel.h"
#include "engine/self_contact.h"
#include "engine/union_find.h"
#include "engine/world_exact.h"

namespace vismap::engine {

namespace {

// Only a closed surface that does not meet itself (embedded) bounds a solid
// that every ray from outside enters at its first face: where it crosses
// itself, it may turn inside out (a fold), and a ray from outside then meets
// a face from behind first, one that no face of the solid hides (CGAL's
// elk.off). Such components are not taken as closed (closed[c] = 0).
void drop_meeting_themselves(const Scene& scene, const WorldFacets& wf, const std::vector<int>& comp,
                             std::vector<char>& closed, int threads) {
  const std::size_t n = comp.size();
  std::vector<int> slot(n, -1);   // per closed component: its list
  std::vector<std::vector<int>> members;
  for (std::size_t f = 0; f < n; ++f) {
    const auto c = static_cast<std::size_t>(comp[f]);
    if (!closed[c]) continue;
    if (slot[c] < 0) {
      slot[c] = static_cast<int>(members.size());
      members.emplace_back();
    }
    members[static_cast<std::size_t>(slot[c])].push_back(static_cast<int>(f));
  }
  if (members.empty()) return;
  // (Its predicates are not counted in the stats: the search stops at the first
  // contact it finds, and which that is depends on the threads.)
  const exact::FilterCounts before = exact::filter_counts;
  const std::vector<char> meets = meets_itself(scene, wf, members, threads);
  exact::filter_counts = before;
  for (std::size_t k = 0; k < members.size(); ++k)
    if (meets[k]) closed[static_cast<std::size_t>(comp[static_cast<std::size_t>(members[k][0])])] = 0;
}

// The input vertices (file indices) of facet w's edge k, lower first, where
// the facet is its whole face (as many corners as the face's ring, the edge's
// two at the same places; else none): two facets of one solid meet along an
// edge between the same two input vertices, where another solid touching it
// along that edge has its own. (Any such joining is safe: each shell is tested
// closed and embedded on its own.)
std::optional<std::pair<std::uint32_t, std::uint32_t>> input_edge(const Scene& scene, const WorldFacet& w,
                                                                   std::uint32_t k) {
  if (w.face < 0 || !scene.holes_of(static_cast<std::size_t>(w.face)).empty()) return std::nullopt;
  const IndexRing& ring = scene.faces[static_cast<std::size_t>(w.face)];
  const std::size_t n = ring.size(), j = (k + 1) % n;
  auto same = [&](std::uint32_t a, std::uint32_t b) {   // (canonical ids: the same point)
    const Vec3 &p = scene.vertices[a], &q = scene.vertices[b];
    return p.x == q.x && p.y == q.y && p.z == q.z;
  };
  if (n != w.v.size() || !same(ring[k], w.v[k]) || !same(ring[j], w.v[j])) return std::nullopt;
  return std::pair(std::min(ring[k], ring[j]), std::max(ring[k], ring[j]));
}

// Facets joined across the pieces they share, on the threads: each facet's
// component, the lowest facet number in it. With `shells`, only across the
// pieces that exactly two facets share, and where more share one, between
// those whose edges join the same two input vertices (input_edge).
std::vector<int> joined_facets(const Scene& scene, const WorldFacets& wf, const std::vector<WorldPiece>& pieces,
                               bool shells, int threads) {
  const int n = static_cast<int>(wf.facets.size()), np = static_cast<int>(pieces.size());
  // (Joined on the threads: a component's number is then its first facet.)
  ConcurrentUnionFind uf(static_cast<std::size_t>(n));
  parallel_chunks(np, 16384, threads, [&](int, Chunk r) {
    for (int i = r.begin; i < r.end; ++i) {
      const auto& s = pieces[static_cast<std::size_t>(i)].sharers;
      if (!shells || s.size() <= 2) {
        for (std::size_t k = 1; k < s.size(); ++k) uf.join(s[0].facet, s[k].facet);
        continue;
      }
      for (std::size_t a = 0; a < s.size(); ++a) {
        const auto ea = input_edge(scene, wf.facets[static_cast<std::size_t>(s[a].facet)], s[a].edge);
        for (std::size_t b = a + 1; ea && b < s.size(); ++b)
          if (ea == input_edge(scene, wf.facets[static_cast<std::size_t>(s[b].facet)], s[b].edge))
            uf.join(s[a].facet, s[b].facet);
      }
    }
  });
  // Each facet's component, once (the loops that follow read it on several threads).
  std::vector<int> comp(static_cast<std::size_t>(n));
  parallel_chunks(n, 16384, threads, [&](int, Chunk r) {
    for (int f = r.begin; f < r.end; ++f) comp[f] = uf.find(f);
  });
  return comp;
}

}  // namespace

ClosedComponents closed_components(const Scene& scene, const WorldFacets& wf, const std::vector<WorldPiece>& pieces,
                                   int threads) {
  const int n = static_cast<int>(wf.facets.size()), np = static_cast<int>(pieces.size());
  // Shells: facets joined where exactly two share a piece, or where more do,
  // those whose edges join the same two input vertices (solids touching along
  // an edge or a face: a building's annex against its wall, a box on another).
  // Each solid is then a shell of its own, closed if its facets close it, and
  // hides its own faces whatever touches it. The connected components (joined
  // across every shared piece) are kept apart for the height fields.
  auto pair = [](const WorldPiece& p) { return p.sharers.size() <= 2; };
  const bool all_pairs = std::all_of(pieces.begin(), pieces.end(), pair);
  ClosedComponents cc;
  if (!all_pairs) cc.connected = joined_facets(scene, wf, pieces, /*shells=*/false, threads);
  std::vector<int> comp = joined_facets(scene, wf, pieces, /*shells=*/!all_pairs, threads);
  std::vector<char> closed(n, 1);
  auto open = [&](int f) {
    std::atomic_ref<char>(closed[static_cast<std::size_t>(comp[f])]).store(0, std::memory_order_relaxed);
  };
  // A piece closes a shell when exactly two of its facets share it, traversing it
  // in opposite directions (consistent orientation).
  parallel_chunks(np, 16384, threads, [&](int, Chunk r) {
    for (int i = r.begin; i < r.end; ++i) {
      const auto& s = pieces[static_cast<std::size_t>(i)].sharers;
      if (s.size() == 2 && s[0].forward != s[1].forward) continue;
      if (s.size() <= 2) {
        for (const auto& sharer : s) open(sharer.facet);
        continue;
      }
      for (const auto& a : s) {
        int same = 0;
        bool opposite = false;
        for (const auto& b : s)
          if (comp[b.facet] == comp[a.facet]) {
            ++same;
            opposite |= b.forward != a.forward;
          }
        if (same != 2 || !opposite) open(a.facet);
      }
    }
  });
  // A non-planar polygon's fan can fold over the polygon's own edge, and a face
  // never hides its own edges (spec: "some face g not sharing e"): an edge between
  // two back-facing pieces may then be visible. Such components are not culled.
  parallel_chunks(n, 16384, threads, [&](int, Chunk r) {
    for (int f = r.begin; f < r.end; ++f)
      if (!wf.facets[f].planar) open(f);
  });
  drop_meeting_themselves(scene, wf, comp, closed, threads);
  cc.side.assign(n, 0);
  // (An open surface, a terrain: no orientation to find, and no per-component
  // sums to make room for, 28 bytes per facet.)
  bool any_closed = false;
  for (int f = 0; f < n && !any_closed; ++f) any_closed = comp[f] == f && closed[f];
  if (!any_closed) {
    cc.component = std::move(comp);
    return cc;
  }

  // The closed components, numbered in the order of their first facets (their
  // roots), each with its origin: the first corner of that facet.
  std::vector<int> number(static_cast<std::size_t>(n), -1);
  int ncomp = 0;
  for (int f = 0; f < n; ++f)
    if (comp[f] == f && closed[f]) number[f] = ncomp++;
  auto origin = [&](int c) -> const Vec3& { return scene.vertices[wf.facets[static_cast<std::size_t>(c)].v[0]]; };
  // Orientation of each closed component: the sign of its signed volume, a sum
  // of tetrahedra from its origin. Each facet's share (and its farthest
  // coordinate) in parallel chunks, summed per component in facet order.
  // Intervals settle the sign unless the volume is (nearly) zero; then it is
  // summed exactly.
  using Interval = CGAL::Interval_nt<false>;
  std::vector<Interval> share(static_cast<std::size_t>(n), Interval(0));
  std::vector<double> reach(static_cast<std::size_t>(n), 0);
  parallel_chunks(n, 8192, threads, [&](int, Chunk r) {
    CGAL::Protect_FPU_rounding<true> upward;
    for (int f = r.begin; f < r.end; ++f) {
      const int c = comp[f];
      if (!closed[c]) continue;
      const auto& v = wf.facets[f].v;
      for (std::size_t k = 1; k + 1 < v.size(); ++k)
        share[f] += world::det<Interval>(origin(c), scene.vertices[v[0]], scene.vertices[v[k]], scene.vertices[v[k + 1]]);
      for (auto id : v) {
        const Vec3& p = scene.vertices[id];
        reach[f] = std::max({reach[f], -p.x, -p.y, -p.z, p.x, p.y, p.z});
      }
    }
  });
  std::vector<Interval> volume(static_cast<std::size_t>(ncomp), Interval(0));
  std::vector<double> far(static_cast<std::size_t>(ncomp), 0);
  {
    CGAL::Protect_FPU_rounding<true> upward;
    for (int f = 0; f < n; ++f) {
      const int c = comp[f];
      if (!closed[c]) continue;
      const auto k = static_cast<std::size_t>(number[c]);
      volume[k] += share[f];
      far[k] = std::max(far[k], reach[f]);
    }
  }
  std::vector<std::int8_t> sign(static_cast<std::size_t>(ncomp), 0);
  std::vector<CGAL::Mpzf> exact;
  for (std::size_t k = 0; k < sign.size(); ++k) {
    // Beyond 2^300 a product of three differences may overflow, and an interval
    // with an infinite bound is not to be trusted (inf * 0 is NaN, which a max
    // can drop): such a component is summed exactly.
    if (!(far[k] <= 0x1p300)) volume[k] = Interval(-1, 1);
    if (volume[k].inf() > 0) sign[k] = 1;
    else if (volume[k].sup() < 0) sign[k] = -1;
    else if (exact.empty()) exact.resize(sign.size());   // (then summed below)
  }
  if (!exact.empty()) {
    for (int f = 0; f < n; ++f) {
      const int c = comp[f];
      if (!closed[c] || sign[static_cast<std::size_t>(number[c])] != 0) continue;
      const auto k = static_cast<std::size_t>(number[c]);
      const auto& v = wf.facets[f].v;
      for (std::size_t j = 1; j + 1 < v.size(); ++j)
        exact[k] = exact[k] + world::det<CGAL::Mpzf>(origin(c), scene.vertices[v[0]], scene.vertices[v[j]], scene.vertices[v[j + 1]]);
    }
    for (std::size_t k = 0; k < sign.size(); ++k)
      if (sign[k] == 0) sign[k] = static_cast<std::int8_t>(exact[k].sign());
  }
  cc.component = std::move(comp);
  parallel_chunks(n, 16384, threads, [&](int, Chunk r) {
    for (int f = r.begin; f < r.end; ++f) {
      const int c = cc.component[f];
      if (closed[c]) cc.side[f] = sign[static_cast<std::size_t>(number[c])];
    }
  });
  return cc;
}

std::vector<NearCap> near_caps(const WorldFacets& wf, const std::vector<WorldPiece>& pieces,
                               const ClosedComponents& cc, const NearPlane& np) {
  // The cut's curves: facets of closed shells joined where the near plane
  // passes from one to the other, across a piece that crosses or touches it
  // (a vertex on the plane joins every facet around it). Each connected curve
  // then lies within one set, of one shell.
  const int n = static_cast<int>(wf.facets.size());
  UnionFind uf(static_cast<std::size_t>(n));
  std::vector<char> touched(n, 0);
  auto closed = [&](const Sharer& s) { return cc.side[s.facet] != 0; };
  for (const WorldPiece& p : pieces) {
    if (std::none_of(p.sharers.begin(), p.sharers.end(), closed)) continue;
    const int za = np.z_sign(p.a), zb = np.z_sign(p.b);
    if (za > 0 && zb > 0) continue;
    if ((za > 0) == (zb > 0) && za != 0 && zb != 0) continue;   // wholly behind
    // (Each sharer joined to the first of its own shell: solids that touch along
    // the piece have cuts, and caps, of their own.)
    for (std::size_t i = 0; i < p.sharers.size(); ++i) {
      if (!closed(p.sharers[i])) continue;
      const int f = p.sharers[i].facet;
      touched[f] = 1;
      for (std::size_t j = 0; j < i; ++j)
        if (cc.component[p.sharers[j].facet] == cc.component[f]) {
          uf.join(p.sharers[j].facet, f);
          break;
        }
    }
  }
  // Each set's box: the facets' cuts and the vertices on the plane.
  std::vector<CGAL::Bbox_2> box(n);
  std::vector<char> has_box(n, 0);
  auto add = [&](int f, const CGAL::Bbox_2& b) {
    const int r = uf.find(f);
    box[r] = has_box[r] ? box[r] + b : b;
    has_box[r] = 1;
  };
  for (int f = 0; f < n; ++f) {
    if (!touched[f]) continue;
    CGAL::Bbox_2 b;
    if (np.facet_cut(f, b)) add(f, b);
    for (auto id : wf.facets[f].v)
      if (np.z_sign(id) == 0) add(f, np.on_plane(id));
  }
  std::vector<NearCap> caps;
  for (int r = 0; r < n; ++r)
    if (has_box[r] && uf.find(r) == r) caps.push_back({cc.component[r], box[r]});
  return caps;
}

std::vector<char> hidden_when_back_facing(const ClosedComponents& cc, const std::vector<NearCap>& caps,
                                          const std::vector<CGAL::Bbox_2>& facet_box, int threads) {
  const std::size_t n = cc.side.size();
  // Each component's caps; past a few dozen, one box holding them all (larger, so
  // still safe) keeps the test per facet short.
  std::vector<std::vector<CGAL::Bbox_2>> of(n);
  for (const NearCap& c : caps) of[static_cast<std::size_t>(c.component)].push_back(c.box);
  for (auto& boxes : of)
    if (boxes.size() > 32) {
      CGAL::Bbox_2 all = boxes[0];
      for (const auto& b : boxes) all += b;
      boxes = {all};
    }
  // Apart: separated by a gap in x or in y (the boxes contain the exact images).
  auto apart = [](const CGAL::Bbox_2& a, const CGAL::Bbox_2& b) {
    return a.xmax() < b.xmin() || b.xmax() < a.xmin() || a.ymax() < b.ymin() || b.ymax() < a.ymin();
  };
  std::vector<char> hidden(n, 0);
  parallel_chunks(static_cast<int>(n), 16384, threads, [&](int, Chunk r) {
    for (auto f = static_cast<std::size_t>(r.begin); f < static_cast<std::size_t>(r.end); ++f) {
      if (cc.side[f] == 0) continue;
      const auto& boxes = of[static_cast<std::size_t>(cc.component[f])];
      hidden[f] = std::all_of(boxes.begin(), boxes.end(), [&](const CGAL::Bbox_2& b) { return apart(facet_box[f], b); });
    }
  });
  return hidden;
}

}  // namespace vismap::engine
