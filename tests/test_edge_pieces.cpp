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
#include <numeric>
#include <optional>
#include <random>
#include <tuple>
#include <vector>

#include "engine/culling.h"
#include "engine/edge_pieces.h"
#include "engine/height_fields.h"

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

// ---- pieces by vertex pairs ---------------------------------------------------------------

// A sheet of n x n squares, two triangles each, over [0, n]^2 at heights from
// `height` (flat stretches make collinear edges along rows and columns), its
// faces in random order, each starting at a random corner.
Scene sheet(int n, std::mt19937_64& rng, double (*height)(int, int)) {
  Scene s;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) s.vertices.push_back({double(i), double(j), height(i, j)});
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      s.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  std::shuffle(s.faces.begin(), s.faces.end(), rng);
  for (auto& f : s.faces) std::rotate(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(rng() % 3), f.end());
  return s;
}
double bumps(int i, int j) { return (i * 7 + j * 3) % 5 == 0 ? 0.5 * i : 0.0; }
double flat(int, int) { return 0.0; }
double slope(int i, int j) { return 0.25 * i - 0.125 * j; }

// pieces_of_vertex_pairs on the vertices numbered as the engine numbers them.
// With their ranks (vertex_pair_ranks).
std::optional<MatchedEdges> vertex_pairs(const Scene& scene, const WorldFacets& wf) {
  std::vector<std::uint32_t> used, local;
  number_by_first_use(wf, scene.vertices.size(), used, local);
  auto pieces = pieces_of_vertex_pairs(scene, wf, local, used.size());
  if (!pieces) return std::nullopt;
  std::vector<PieceRank> rank = vertex_pair_ranks(*pieces);
  return MatchedEdges{std::move(*pieces), std::move(rank)};
}

// What pieces_of_vertex_pairs gives, as engine_pieces keys them, after checking
// their order: by first sharer, then rank, which is the piece's vertex pair.
std::optional<Pieces> vertex_pair_pieces(const Scene& scene, const WorldFacets& wf) {
  const auto got = vertex_pairs(scene, wf);
  if (!got) return std::nullopt;
  Pieces out;
  std::tuple<int, std::uint32_t, std::uint32_t> last{-1, 0, 0};
  for (std::size_t i = 0; i < got->pieces.size(); ++i) {
    const WorldPiece& wp = got->pieces[i];
    const std::uint32_t lo = std::min(wp.a, wp.b), hi = std::max(wp.a, wp.b);
    const std::tuple<int, std::uint32_t, std::uint32_t> place{wp.sharers[0].facet, lo, hi};
    EXPECT_LT(last, place) << "pieces out of order";
    last = place;
    EXPECT_EQ(got->rank[i].cells, std::uint64_t{lo} << 32 | hi);
    auto& slot = out[Key{lo, hi}];
    EXPECT_TRUE(slot.second.empty()) << "piece " << wp.a << "-" << wp.b << " given twice";
    slot.first = Key{wp.a, wp.b};
    for (const Sharer& sh : wp.sharers) slot.second.emplace_back(sh.facet, std::uint32_t{sh.edge}, sh.forward != 0);
    EXPECT_TRUE(std::is_sorted(slot.second.begin(), slot.second.end()));
  }
  return out;
}

// On a disk of triangles where no vertex lies inside an edge, vertex pairs give
// match_edges' pieces: the same ends, the same way round, the same sharers.
TEST(EdgePieces, VertexPairsGiveMatchEdgesPiecesOnADisk) {
  std::mt19937_64 rng(77);
  int compared = 0;
  for (auto height : {bumps, flat, slope})
    for (int n : {1, 2, 5, 9}) {
      const Scene scene = sheet(n, rng, height);
      const WorldFacets wf = make_world_facets(scene);
      const auto got = vertex_pair_pieces(scene, wf);
      ASSERT_TRUE(got.has_value()) << n;
      EXPECT_EQ(*got, engine_pieces(scene, wf, 20)) << n;
      compared += static_cast<int>(got->size());
      // Renumbered for the facets in another order (as each of many views
      // takes the pieces matched once), what matching them in that order gives.
      std::vector<std::uint32_t> order(wf.facets.size()), new_index(order.size());
      std::iota(order.begin(), order.end(), 0u);
      std::shuffle(order.begin(), order.end(), rng);
      WorldFacets reordered = wf;
      for (std::size_t k = 0; k < order.size(); ++k) {
        reordered.facets[k] = wf.facets[order[k]];
        new_index[order[k]] = static_cast<std::uint32_t>(k);
      }
      const MatchedEdges renumbered = renumber_facets(*vertex_pairs(scene, wf), new_index);
      const auto direct = vertex_pairs(scene, reordered);
      ASSERT_TRUE(direct.has_value());
      ASSERT_EQ(renumbered.pieces.size(), direct->pieces.size());
      for (std::size_t i = 0; i < direct->pieces.size(); ++i) {
        const WorldPiece &x = renumbered.pieces[i], &y = direct->pieces[i];
        ASSERT_EQ(std::pair(x.a, x.b), std::pair(y.a, y.b)) << i;
        ASSERT_EQ(x.sharers.size(), y.sharers.size()) << i;
        for (std::size_t k = 0; k < x.sharers.size(); ++k) {
          EXPECT_EQ(x.sharers[k].facet, y.sharers[k].facet);
          EXPECT_EQ(x.sharers[k].edge, y.sharers[k].edge);
          EXPECT_EQ(x.sharers[k].forward, y.sharers[k].forward);
        }
      }
    }
  EXPECT_GT(compared, 500);
}

// On threads, in parts and chunks (a sheet large enough for several of each:
// 33 800 triangles, 17 161 vertices), the pieces one thread gives, which are
// match_edges'.
TEST(EdgePieces, VertexPairsAreTheSameOnEveryThreadCount) {
  std::mt19937_64 rng(79);
  const Scene scene = sheet(130, rng, bumps);
  const WorldFacets wf = make_world_facets(scene);
  const auto got = vertex_pair_pieces(scene, wf);
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(*got, engine_pieces(scene, wf, 20));
  std::vector<std::uint32_t> used, local;
  number_by_first_use(wf, scene.vertices.size(), used, local);
  const auto one = pieces_of_vertex_pairs(scene, wf, local, used.size(), 1);
  ASSERT_TRUE(one.has_value());
  EXPECT_EQ(one->size(), used.size() + wf.facets.size() - 1);   // (E = V + F - 1)
  for (int threads : {2, 3}) {
    const auto many = pieces_of_vertex_pairs(scene, wf, local, used.size(), threads);
    ASSERT_TRUE(many.has_value()) << threads;
    ASSERT_EQ(many->size(), one->size()) << threads;
    for (std::size_t i = 0; i < one->size(); ++i) {
      const WorldPiece &x = (*one)[i], &y = (*many)[i];
      ASSERT_EQ(std::pair(x.a, x.b), std::pair(y.a, y.b)) << i;
      ASSERT_EQ(x.sharers.size(), y.sharers.size()) << i;
      for (std::size_t k = 0; k < x.sharers.size(); ++k)
        ASSERT_EQ(std::tuple(x.sharers[k].facet, std::uint32_t{x.sharers[k].edge}, std::uint32_t{x.sharers[k].forward}),
                  std::tuple(y.sharers[k].facet, std::uint32_t{y.sharers[k].edge}, std::uint32_t{y.sharers[k].forward}))
            << i;
    }
  }
}

// Nothing but a disk of triangles (V - E + F = 1, no edge of three) is matched
// by vertex pairs: a closed surface, a ring, a quad, a fin, two sheets, and
// sheets with a vertex inside a neighbour's edge (a T-junction: the slit it
// leaves is a hole).
TEST(EdgePieces, VertexPairsRefuseWhatIsNoDisk) {
  std::mt19937_64 rng(78);
  auto refused = [](const Scene& scene) {
    const WorldFacets wf = make_world_facets(scene);
    return !vertex_pair_pieces(scene, wf).has_value();
  };
  Scene tetrahedron;
  tetrahedron.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tetrahedron.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  EXPECT_TRUE(refused(tetrahedron));
  Scene ring = sheet(3, rng, bumps);
  ring.faces.erase(std::remove_if(ring.faces.begin(), ring.faces.end(),
                                  [&](const auto& f) {
                                    return std::all_of(f.begin(), f.end(), [&](std::uint32_t v) {
                                      const Vec3& p = ring.vertices[v];
                                      return p.x >= 1 && p.x <= 2 && p.y >= 1 && p.y <= 2;
                                    });
                                  }),
                   ring.faces.end());
  EXPECT_TRUE(refused(ring));
  Scene quad = sheet(2, rng, flat);
  quad.faces.push_back({0, 1, 4, 3});
  quad.vertices.push_back({0, 0, -1});   // (unused: the quad lies on the sheet's first square)
  EXPECT_TRUE(refused(quad));
  Scene fin = sheet(2, rng, flat);
  fin.vertices.push_back({0.5, 0.5, 1});
  fin.faces.push_back({0, 4, static_cast<std::uint32_t>(fin.vertices.size() - 1)});
  EXPECT_TRUE(refused(fin));
  Scene two = sheet(2, rng, flat);
  const auto base = static_cast<std::uint32_t>(two.vertices.size());
  for (Vec3 p : sheet(2, rng, flat).vertices) two.vertices.push_back({p.x + 5, p.y, p.z});
  for (auto f : sheet(2, rng, flat).faces) {
    for (auto& v : f) v += base;
    two.faces.push_back(f);
  }
  EXPECT_TRUE(refused(two));
  // T-junctions: a square's edge split at its midpoint on one side only, inside
  // the sheet and at its border; match_edges splits its neighbour's piece there.
  for (int border : {0, 1}) {
    Scene t = sheet(3, rng, flat);
    const std::uint32_t a = border ? 0 : 5, b = border ? 1 : 6;   // (0, 0)-(1, 0) or (1, 1)-(2, 1)
    t.vertices.push_back({(t.vertices[a].x + t.vertices[b].x) / 2, t.vertices[a].y, 0});
    const auto m = static_cast<std::uint32_t>(t.vertices.size() - 1);
    // The triangle below (or, at the border, a new one) takes the midpoint.
    const Vec3 below{t.vertices[a].x + 0.5, t.vertices[a].y - 1, 0};
    t.vertices.push_back(below);
    const auto c = static_cast<std::uint32_t>(t.vertices.size() - 1);
    if (border) {
      t.faces.push_back({a, m, c});
      t.faces.push_back({m, b, c});
    } else {
      auto it = std::find_if(t.faces.begin(), t.faces.end(), [&](const auto& f) {
        return std::count(f.begin(), f.end(), a) && std::count(f.begin(), f.end(), b) &&
               std::all_of(f.begin(), f.end(), [&](std::uint32_t v) { return t.vertices[v].y <= t.vertices[a].y; });
      });
      ASSERT_NE(it, t.faces.end());
      const std::uint32_t o = *std::find_if(it->begin(), it->end(), [&](std::uint32_t v) { return v != a && v != b; });
      t.faces.erase(it);
      t.faces.push_back({a, m, o});
      t.faces.push_back({m, b, o});
      t.vertices.pop_back();
    }
    const WorldFacets wf = make_world_facets(t);
    int split = 0;
    reference(t, wf, split);
    EXPECT_GT(split, 0) << border;
    EXPECT_TRUE(refused(t)) << border;
    // With a second sheet apart (V - E + F then 1 in all), vertex pairs match
    // it, missing the split; the height fields' certificate then refuses the
    // sheet with the T-junction, and so the scene (the engine's condition: one
    // height field of every facet).
    const auto base = static_cast<std::uint32_t>(t.vertices.size());
    t.vertices.push_back({10, 10, 0});
    t.vertices.push_back({11, 10, 0});
    t.vertices.push_back({10, 11, 0});
    t.faces.push_back({base, base + 1, base + 2});
    const WorldFacets both = make_world_facets(t);
    const auto pairs = vertex_pairs(t, both);
    ASSERT_TRUE(pairs.has_value()) << border;
    EXPECT_NE(*vertex_pair_pieces(t, both), engine_pieces(t, both, 20));
    const ClosedComponents cc = closed_components(t, both, pairs->pieces);
    const std::vector<int> label = height_field_components(t, both, pairs->pieces, cc.connected_components());
    for (std::size_t f = 0; f < both.facets.size(); ++f) {
      const bool in_t_sheet = both.facets[f].face + 1 < static_cast<int>(t.faces.size());
      if (in_t_sheet) {
        EXPECT_LT(label[f], 0) << border << " " << f;
      }
    }
  }
}

}  // namespace
