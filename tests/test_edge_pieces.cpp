// Edge matching (engine/edge_pieces.cpp) against a brute-force exact reference.
// Triangles are laid with edges along a few 3D lines (integer points scaled by
// powers of two, so every point is exactly on its line: shared edges, collinear
// overlaps, containment, T-junctions), at magnitudes from 2^-1000 to 2^1000.
// The reference splits every edge at the end points of all edges on its line
// (exact rational collinearity, O(E^2)); match_edges must give the same pieces
// with the same sharers, whatever coarseness it first tells lines apart by
// (cell_bits 0: everything collides and GMP decides; 52: every inexact interval
// straddles a border; 20: the default).
#include <gtest/gtest.h>
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "engine/edge_pieces.h"

namespace {

using namespace vismap;
using namespace vismap::engine;

struct Q3 {
  mpq_class x, y, z;
};
Q3 q3(const Vec3& v) { return {v.x, v.y, v.z}; }

// p, q, r on one line (exact).
bool collinear(const Q3& p, const Q3& q, const Q3& r) {
  const mpq_class ax = q.x - p.x, ay = q.y - p.y, az = q.z - p.z;
  const mpq_class bx = r.x - p.x, by = r.y - p.y, bz = r.z - p.z;
  return ay * bz == az * by && az * bx == ax * bz && ax * by == ay * bx;
}

// Position of r along p -> q (r on the line): the parameter's numerator over |q - p|^2.
mpq_class along(const Q3& p, const Q3& q, const Q3& r) {
  return (r.x - p.x) * (q.x - p.x) + (r.y - p.y) * (q.y - p.y) + (r.z - p.z) * (q.z - p.z);
}

using Key = std::pair<std::uint32_t, std::uint32_t>;            // piece, lower id first
using Sharers = std::vector<std::tuple<int, int, bool>>;        // (facet, edge, forward), sorted
using Pieces = std::map<Key, std::pair<Key, Sharers>>;          // -> (a, b as given), sharers

Pieces reference(const Scene& scene, const WorldFacets& wf, int& split_edges) {
  struct E {
    int facet, edge;
    std::uint32_t p, q;
  };
  std::vector<E> edges;
  for (int f = 0; f < static_cast<int>(wf.facets.size()); ++f) {
    const auto& v = wf.facets[f].v;
    for (std::size_t i = 0; i < v.size(); ++i) edges.push_back({f, static_cast<int>(i), v[i], v[(i + 1) % v.size()]});
  }
  std::vector<Q3> pt(scene.vertices.size());
  for (std::size_t i = 0; i < pt.size(); ++i) pt[i] = q3(scene.vertices[i]);
  Pieces out;
  for (const E& e : edges) {
    const Q3 &p = pt[e.p], &q = pt[e.q];
    const mpq_class len = along(p, q, q);
    // Break points: end points of every edge on this line, inside this edge.
    std::vector<std::pair<mpq_class, std::uint32_t>> cuts{{0, e.p}, {len, e.q}};
    for (const E& o : edges) {
      if (!collinear(p, q, pt[o.p]) || !collinear(p, q, pt[o.q])) continue;
      for (std::uint32_t w : {o.p, o.q}) {
        const mpq_class t = along(p, q, pt[w]);
        if (t > 0 && t < len) cuts.emplace_back(t, w);
      }
    }
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end(), [](auto& a, auto& b) { return a.first == b.first; }),
               cuts.end());
    split_edges += cuts.size() > 2;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      const std::uint32_t u = cuts[i].second, w = cuts[i + 1].second;
      // a -> b runs the way the first moving axis increases.
      const Vec3 &vu = scene.vertices[u], &vw = scene.vertices[w];
      const bool up = vu.x != vw.x ? vu.x < vw.x : vu.y != vw.y ? vu.y < vw.y : vu.z < vw.z;
      const Key ab = up ? Key{u, w} : Key{w, u};
      auto& slot = out[Key{std::min(u, w), std::max(u, w)}];
      slot.first = ab;
      slot.second.emplace_back(e.facet, e.edge, false);   // (forward: below)
    }
  }
  for (auto& [k, v] : out) std::sort(v.second.begin(), v.second.end());
  return out;
}

// With each sharer's direction: whether the facet's edge p -> q runs from a to b.
Pieces reference_forward(const Scene& scene, const WorldFacets& wf, int& split_edges) {
  Pieces r = reference(scene, wf, split_edges);
  for (auto& [k, v] : r) {
    const Vec3 &a = scene.vertices[v.first.first], &b = scene.vertices[v.first.second];
    for (auto& [f, ed, fwd] : v.second) {
      const auto& fv = wf.facets[f].v;
      const Vec3 &p = scene.vertices[fv[ed]], &q = scene.vertices[fv[(ed + 1) % fv.size()]];
      // Same direction as a -> b: the dot product of the two directions (exact in GMP).
      const mpq_class d = (mpq_class(q.x) - p.x) * (mpq_class(b.x) - a.x) +
                          (mpq_class(q.y) - p.y) * (mpq_class(b.y) - a.y) +
                          (mpq_class(q.z) - p.z) * (mpq_class(b.z) - a.z);
      fwd = d > 0;
    }
  }
  return r;
}

Pieces engine_pieces(const Scene& scene, const WorldFacets& wf, int bits) {
  Pieces out;
  for (const WorldPiece& wp : match_edges(scene, wf, bits)) {
    const Key k{std::min(wp.a, wp.b), std::max(wp.a, wp.b)};
    EXPECT_EQ(out.count(k), 0u) << "piece " << wp.a << "-" << wp.b << " given twice";
    auto& slot = out[k];
    slot.first = Key{wp.a, wp.b};
    for (const Sharer& s : wp.sharers) slot.second.emplace_back(s.facet, std::uint32_t{s.edge}, s.forward != 0);
    EXPECT_TRUE(std::is_sorted(slot.second.begin(), slot.second.end()));
  }
  return out;
}

Scene lines_scene(std::mt19937_64& rng, int scale_exp) {
  Scene s;
  std::uniform_int_distribution<int> base(-40, 40), dir(-4, 4), t(-6, 6), nlines(1, 5);
  const double scale = std::ldexp(1.0, scale_exp);
  struct L {
    int b[3], d[3];
  };
  std::vector<L> lines(static_cast<std::size_t>(nlines(rng)));
  for (L& l : lines) {
    for (int k = 0; k < 3; ++k) { l.b[k] = base(rng); l.d[k] = dir(rng); }
    if (l.d[0] == 0 && l.d[1] == 0 && l.d[2] == 0) l.d[rng() % 3] = 1;
    // Some lines along an axis, as in CAD models.
    if (rng() % 3 == 0) { const int k = static_cast<int>(rng() % 3); for (int j = 0; j < 3; ++j) if (j != k) l.d[j] = 0; if (l.d[k] == 0) l.d[k] = 1; }
  }
  auto add = [&](double x, double y, double z) {
    s.vertices.push_back(Vec3{x * scale, y * scale, z * scale});
    return static_cast<std::uint32_t>(s.vertices.size() - 1);
  };
  const int triangles = 30;
  for (int i = 0; i < triangles; ++i) {
    const L& l = lines[rng() % lines.size()];
    int t1 = t(rng), t2 = t(rng);
    if (t1 == t2) t2 = t1 + 1;
    const auto a = add(l.b[0] + t1 * l.d[0], l.b[1] + t1 * l.d[1], l.b[2] + t1 * l.d[2]);
    const auto b = add(l.b[0] + t2 * l.d[0], l.b[1] + t2 * l.d[1], l.b[2] + t2 * l.d[2]);
    // The third corner: off the line (usually), sometimes on another line.
    std::uint32_t c;
    if (rng() % 2) {
      const L& m = lines[rng() % lines.size()];
      const int t3 = t(rng);
      c = add(m.b[0] + t3 * m.d[0], m.b[1] + t3 * m.d[1], m.b[2] + t3 * m.d[2]);
    } else {
      c = add(base(rng), base(rng), base(rng));
    }
    s.faces.push_back(rng() % 2 ? std::vector<std::uint32_t>{a, b, c} : std::vector<std::uint32_t>{b, a, c});
  }
  return s;
}

TEST(EdgePieces, MatchesExactReferenceAtEveryCoarseness) {
  std::mt19937_64 rng(2026);
  int shared = 0, split = 0;
  for (int iter = 0; iter < 120; ++iter) {
    const int exps[] = {0, -30, 40, -1000, 1000};
    const Scene scene = lines_scene(rng, exps[iter % 5]);
    const WorldFacets wf = make_world_facets(scene);
    const Pieces want = reference_forward(scene, wf, split);
    for (int bits : {20, 0, 52, 50}) {
      const Pieces got = engine_pieces(scene, wf, bits);
      ASSERT_EQ(got, want) << "scene " << iter << ", cell_bits " << bits;
    }
    for (const auto& [k, v] : want) shared += v.second.size() > 1;
  }
  // The scenes must exercise what they are for: pieces shared by several
  // edges, and edges split where collinear edges end inside them.
  EXPECT_GT(shared, 500);
  EXPECT_GT(split, 500);
}

// A line's cells are found from doubles with error bounds where those decide:
// they must be the exact key's cells on every line, above all on lines whose
// slopes and offsets lie within a few units in the last place of a cell's
// border (made by multiplying a border value by an odd divisor and moving a
// few ulps), at every coarseness, at magnitudes where the doubles must give
// up, and on lines along or across the axes (exact zero differences). (It fails
// when either error bound is cut to 0.5u: checked.)
TEST(EdgePieces, LineCellsFromDoublesAreTheExactKeysCells) {
  std::mt19937_64 rng(53);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> small(-6, 6);
  auto step = [&](double x, int ulps) {
    for (; ulps > 0; --ulps) x = std::nextafter(x, HUGE_VAL);
    for (; ulps < 0; ++ulps) x = std::nextafter(x, -HUGE_VAL);
    return x;
  };
  for (int iter = 0; iter < 200000; ++iter) {
    const int bits = std::array{20, 20, 20, 0, 1, 8, 33, 51, 52}[iter % 9];
    Vec3 p{unit(rng), unit(rng), unit(rng)}, q{unit(rng), unit(rng), unit(rng)};
    switch (iter % 6) {
      case 0: break;   // (general)
      case 1: {        // slopes and an offset within a few ulps of a border
        auto border = [&] { return std::ldexp(std::floor(unit(rng) * 0x1p21), -21); };
        const double d = 3.0 * std::ldexp(1.0, small(rng) / 3), sy = border(), sz = border();
        p.x = 1 + std::ldexp(double(small(rng)), -20);
        p.y = step(border() + p.x * sy, small(rng));   // (the offset p_y - p_x s_y)
        q.x = p.x + d;
        q.y = step(p.y + sy * d, small(rng));          // (the slope (q_y - p_y) / d)
        q.z = step(p.z + sz * d, small(rng));
        break;
      }
      case 2: q.y = p.y; break;                  // (a zero slope)
      case 3: q.x = p.x; q.z = p.z; break;       // (along y only)
      case 4: {                                  // (magnitudes the doubles leave to the exact key)
        const int e = std::array{-1000, -950, -890, 880, 950, 1000}[rng() % 6];
        p = {std::ldexp(p.x, e), std::ldexp(p.y, e), std::ldexp(p.z, e)};
        q = {std::ldexp(q.x, e), std::ldexp(q.y, e), std::ldexp(q.z, e)};
        break;
      }
      case 5: {                                  // (integer points: exact or short slopes)
        p = {double(small(rng)), double(small(rng)), double(small(rng))};
        q = {double(small(rng)), double(small(rng)), double(small(rng))};
        if (p.x == q.x && p.y == q.y && p.z == q.z) q.z += 1;
        break;
      }
    }
    ASSERT_EQ(line_cells(p, q, bits), line_cells(p, q, bits, /*exact_only=*/true))
        << "iter " << iter << ", bits " << bits << std::hexfloat << ": p " << p.x << ' ' << p.y << ' ' << p.z
        << ", q " << q.x << ' ' << q.y << ' ' << q.z;
  }
}

// Many views match the edges once and renumber the facets for each view's order
// (renumber_facets): that must give exactly what matching the reordered facets
// gives, pieces, sharers and order, at every coarseness and on several threads.
TEST(EdgePieces, RenumberedFacetsMatchAsIfMatchedInTheirNewOrder) {
  std::mt19937_64 rng(1982);
  std::int64_t compared = 0, moved = 0;
  for (int iter = 0; iter < 60; ++iter) {
    const int exps[] = {0, -30, 40, -1000, 1000};
    const Scene scene = lines_scene(rng, exps[iter % 5]);
    const WorldFacets wf = make_world_facets(scene);
    std::vector<std::uint32_t> order(wf.facets.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<std::uint32_t>(k);
    std::shuffle(order.begin(), order.end(), rng);
    WorldFacets reordered = wf;
    std::vector<std::uint32_t> new_index(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
      reordered.facets[k] = wf.facets[order[k]];
      new_index[order[k]] = static_cast<std::uint32_t>(k);
    }
    for (int bits : {20, 0, 52}) {
      for (int threads : {1, 3}) {
        const MatchedEdges got = renumber_facets(match_edges_ranked(scene, wf, bits, threads), new_index, threads);
        const MatchedEdges want = match_edges_ranked(scene, reordered, bits, threads);
        ASSERT_EQ(got.pieces.size(), want.pieces.size()) << iter;
        for (std::size_t i = 0; i < want.pieces.size(); ++i) {
          const WorldPiece &g = got.pieces[i], &w = want.pieces[i];
          ASSERT_EQ(std::pair(g.a, g.b), std::pair(w.a, w.b)) << "scene " << iter << ", piece " << i;
          ASSERT_EQ(g.sharers.size(), w.sharers.size()) << "scene " << iter << ", piece " << i;
          for (std::size_t k = 0; k < w.sharers.size(); ++k) {
            EXPECT_EQ(g.sharers[k].facet, w.sharers[k].facet);
            EXPECT_EQ(g.sharers[k].edge, w.sharers[k].edge);
            EXPECT_EQ(g.sharers[k].forward, w.sharers[k].forward);
          }
          EXPECT_FALSE(got.rank[i] < want.rank[i] || want.rank[i] < got.rank[i]);
          ++compared;
        }
        const MatchedEdges before = match_edges_ranked(scene, wf, bits, threads);
        for (std::size_t i = 0; i < before.pieces.size(); ++i)
          moved += before.pieces[i].a != want.pieces[i].a || before.pieces[i].b != want.pieces[i].b;
      }
    }
  }
  EXPECT_GT(compared, 10000);
  EXPECT_GT(moved, 1000);   // (the new order is not the old one)
}

}  // namespace
