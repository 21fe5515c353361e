#include "engine/screen_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "engine/cap_inside.h"
#include "engine/culling.h"
#include "engine/edge_pieces.h"
#include "engine/engine_run.h"
#include "engine/height_fields.h"
#include "engine/lazy_leaves.h"
#include "engine/morton.h"
#include "engine/parallel.h"
#include "engine/world_exact.h"

namespace vismap::engine {
VISMAP_KERNEL_BEGIN
namespace {

// Two counts kept per chunk of facets, side by side on the threads (a cache
// line each), then summed.
struct alignas(64) ChunkCounts {
  std::int64_t first = 0, second = 0;
};
std::pair<std::int64_t, std::int64_t> summed(const std::vector<ChunkCounts>& counts) {
  std::pair<std::int64_t, std::int64_t> total{0, 0};
  for (const ChunkCounts& c : counts) {
    total.first += c.first;
    total.second += c.second;
  }
  return total;
}

struct Homogeneous {
  FT X, Y, Z, W;
};

Homogeneous transform(const View& view, const FT& x, const FT& y, const FT& z) {
  const auto& m = view.m;
  auto row = [&](int r) { return FT(m[r][0]) * x + FT(m[r][1]) * y + FT(m[r][2]) * z + FT(m[r][3]); };
  if (!view.perspective) return {row(0), row(1), row(2), FT(1)};
  return {row(0), row(1), row(2), row(3)};
}

// Arithmetic done once per facet, outside the kernel: GMP rationals (plain
// doubles in the float variant), the result made a kernel number (a leaf).
#ifdef VISMAP_FLOAT_KERNEL
using Num = double;
double num(const FT& x) { return x; }
#else
using Num = mpq_class;
mpq_class num(const FT& x) { return to_mpq(x); }
#endif

// sum_c m[c] v[c] + m[3] in doubles, where every product and every partial sum
// is exact (checked: fma residuals and two-sum errors zero, nothing near
// underflow or overflow); false otherwise. Views along an axis (CAD's front,
// top and side views) project most vertices this way, without GMP.
bool exact_in_doubles(const std::array<double, 4>& m, const Vec3& p, double& out) {
  const double v[3] = {p.x, p.y, p.z};
  double acc = m[3];
  for (int c = 0; c < 3; ++c) {
    if (m[c] == 0 || v[c] == 0) continue;
    const double prod = m[c] * v[c];
    if (!(std::abs(prod) > 0x1p-960 && std::abs(prod) < 0x1p960) || std::fma(m[c], v[c], -prod) != 0) return false;
    const double sum = acc + prod, back = sum - acc;
    if (!(std::abs(sum) < 0x1p960) || (acc - (sum - back)) + (prod - back) != 0) return false;
    acc = sum;
  }
  out = acc;
  return true;
}

// The screen scale: the power of two 2^k that every screen coordinate (x, y and
// depth) is multiplied by inside the engines, chosen from a bound on their size
// (doubles, used for nothing else) so that they lie within 2^-64..2^64 of 1
// when the scene does not. Interval filters then never overflow, even on
// products of several coordinates (at 1e300 they would: an infinite bound can
// turn into a NaN that a min or max then drops, and CGAL's lazy line
// intersection reads an overflow as "no intersection"); nor do they underflow
// to useless zeros at 1e-300. Scaling by 2^k is exact and changes no decision;
// the map's vertices are scaled back once, when it is complete (unscale_map).
int screen_scale(const Scene& scene, const std::vector<std::uint32_t>& used, const View& view) {
  double far = 0;   // the largest |coordinate| of a used vertex (or, in perspective, of the eye)
  for (auto id : used) {
    const Vec3& p = scene.vertices[id];
    far = std::max({far, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  }
  if (far == 0) return 0;
  auto row_log2 = [&](int r) {   // log2 of an upper bound on |row r, without its offset|
    const double a = std::max({std::abs(view.m[r][0]), std::abs(view.m[r][1]), std::abs(view.m[r][2])});
    return a == 0 ? -2000 : std::ilogb(a) + 3;
  };
  int e = -2000;   // |every screen coordinate| <= 2^e
  if (!view.perspective) {
    for (int r = 0; r < 3; ++r) e = std::max(e, row_log2(r) + std::ilogb(far) + 1);
  } else {
    // |X/W| <= |row 0| |p - eye| / near, as W >= near wherever anything is kept
    // (the near plane is Z = 0, Z = W - near); likewise Y. Depth is in [0, 1).
    far = std::max({far, std::abs(view.eye.x), std::abs(view.eye.y), std::abs(view.eye.z)});
    const double near = view.m[3][3] - view.m[2][3];
    if (!(near > 0)) return 0;
    e = std::max(row_log2(0), row_log2(1)) + std::ilogb(far) + 2 - std::ilogb(near);
  }
  if (e > 64) return -e;
  if (e < -64 && !view.perspective) return -e;
  return 0;
}

// x * 2^k, exactly: a double when it still is one exactly.
// A lines-only drawing may leave the images for later (make_screen_scene); the
// float variant makes them at once (its numbers are doubles).
#ifdef VISMAP_FLOAT_KERNEL
constexpr bool can_defer_images = false;
#else
constexpr bool can_defer_images = true;
#endif

// x 2^k as a double where it is one exactly (no underflow, no overflow).
bool scales_exactly(double x, int k, double& y) {
  y = std::ldexp(x, k);
  return x == 0 || (std::isfinite(y) && std::abs(y) >= 0x1p-1022);
}
FT scaled(double x, int k) {
  double y;
  if (scales_exactly(x, k, y)) return FT(y);
  mpq_class q(x);
  times_pow2(q, k);
  return from_mpq(q);
}
#ifndef VISMAP_FLOAT_KERNEL
// The interval of scaled(x, k), without making the number where it is a double.
Interval scaled_interval(double x, int k) {
  double y;
  return scales_exactly(x, k, y) ? Interval(y) : approx_of(scaled(x, k));
}
#endif

CGAL::Bbox_2 box_of(const P3& p) {
  auto ix = CGAL::to_interval(p.x), iy = CGAL::to_interval(p.y);
  return CGAL::Bbox_2(ix.first, iy.first, ix.second, iy.second);
}
// The box of an image left for later, from its kept intervals (as box_of it).
CGAL::Bbox_2 box_of(const ImageBounds& b) { return CGAL::Bbox_2(b.x.inf(), b.y.inf(), b.x.sup(), b.y.sup()); }
// The box of a corner or curve end of ss: its kept intervals' where its image is
// left for later.
CGAL::Bbox_2 box_at(const ScreenScene& ss, const P3& p) {
  const std::ptrdiff_t u = ss.kept_place(p);
  return u >= 0 ? box_of(ss.kept_bounds(u)) : box_of(p);
}

// World point on segment p->q where the near plane (Z = 0) cuts it.
struct WorldPoint {
  FT x, y, z;
};
WorldPoint cut_at_near(const WorldPoint& p, const WorldPoint& q, const FT& zp, const FT& zq) {
  FT t = zp / (zp - zq);
  return {p.x + t * (q.x - p.x), p.y + t * (q.y - p.y), p.z + t * (q.z - p.z)};
}

// A world facet's corners o, p, q that span its plane: the first corner and the
// first two consecutive ones after it that are not collinear with it.
struct Spanning {
  Vec3 o, p, q;
};

// The crease test n1.n2 < c |n1||n2|, exactly, without square roots: with
// d = n1.n2 and l = |n1|^2 |n2|^2, for c >= 0: d < 0 or d^2 < c^2 l; for c < 0:
// d < 0 and d^2 > c^2 l. Signs from intervals first, exactly where they cannot tell.
template <class N>
struct CreaseTerms {
  std::array<N, 3> n1, n2;
  N d;
  CreaseTerms(const Spanning& f, const Spanning& g)
      : n1(world::normal_of<N>(f.o, f.p, f.q)), n2(world::normal_of<N>(g.o, g.p, g.q)),
        d(n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2]) {}
  N e(double c) const {   // d^2 - c^2 l
    const N l = (n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]) * (n2[0] * n2[0] + n2[1] * n2[1] + n2[2] * n2[2]);
    return d * d - N(c) * N(c) * l;
  }
};
template <class N>
std::pair<N, N> crease_terms(const Spanning& f, const Spanning& g, double c) {
  const CreaseTerms<N> t(f, g);
  return {t.d, t.e(c)};
}
// The same signs on doubles, where a static error bound settles them. With D
// the largest |coordinate| of the four edge vectors, each normal component is
// off by at most 8.1 u D^2 (u = 2^-53), d by 158 u D^4 < 2^-45 D^4 and
// d^2 - c^2 l by 8568 u D^8 < 2^-39 D^8 (|c| <= 1): the bounds below are 32
// times those. False where D is 0 or outside 2^-100..2^100 (products of degree
// 8 must neither underflow nor overflow). The edge vectors are taken once, for
// D and for the normals (normal_of's products): this is asked of every edge
// between two faces that face the same way, most edges of a smooth mesh.
bool crease_signs_on_doubles(const Spanning& f, const Spanning& g, double c, int& sd, int& se) {
  const std::array<double, 12> e4{f.p.x - f.o.x, f.p.y - f.o.y, f.p.z - f.o.z, f.q.x - f.o.x, f.q.y - f.o.y, f.q.z - f.o.z,
                                  g.p.x - g.o.x, g.p.y - g.o.y, g.p.z - g.o.z, g.q.x - g.o.x, g.q.y - g.o.y, g.q.z - g.o.z};
  double D = 0;
  for (double x : e4) D = std::max(D, std::abs(x));
  if (!(D >= 0x1p-100 && D <= 0x1p100)) return false;
  auto normal = [&](std::size_t k) -> std::array<double, 3> {   // (k: 0 for f, 6 for g)
    const double ax = e4[k], ay = e4[k + 1], az = e4[k + 2], bx = e4[k + 3], by = e4[k + 4], bz = e4[k + 5];
    return {ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx};
  };
  const std::array<double, 3> n1 = normal(0), n2 = normal(6);
  const double d = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2];
  const double l = (n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]) * (n2[0] * n2[0] + n2[1] * n2[1] + n2[2] * n2[2]);
  const double e = d * d - c * c * l;
  const double D4 = (D * D) * (D * D), d_bound = 0x1p-40 * D4, e_bound = 0x1p-34 * (D4 * D4);
  if (std::abs(d) <= d_bound || std::abs(e) <= e_bound) return false;
  sd = d > 0 ? 1 : -1;
  se = e > 0 ? 1 : -1;
  return true;
}

bool is_crease(const Spanning& f, const Spanning& g, double c) {
  int sd = 2, se = 2;   // signs of d and of d^2 - c^2 l (2: not known)
  // (Products of degree 8: coordinates within 2^100 cannot overflow them.)
  const bool settled = crease_signs_on_doubles(f, g, c, sd, se);
  if (!settled && world::within(100, {&f.o, &f.p, &f.q, &g.o, &g.p, &g.q})) {
    CGAL::Protect_FPU_rounding<true> upward;
    const auto [d, e] = crease_terms<Interval>(f, g, c);
    sd = d.inf() > 0 ? 1 : d.sup() < 0 ? -1 : 2;
    se = e.inf() > 0 ? 1 : e.sup() < 0 ? -1 : 2;
  }
  if (sd == 2 || se == 2) {
    // Exactly, d first: where it is 0 (faces at a right angle: every edge of a
    // box, the case the filters cannot settle), d^2 - c^2 l = -c^2 l has the
    // sign of -c^2 (l > 0: a facet's spanning corners are not collinear).
    const CreaseTerms<CGAL::Mpzf> t(f, g);
    sd = t.d.sign();
    if (sd == 0) return c > 0;
    se = t.e(c).sign();
  }
  if (c >= 0) return sd < 0 || se < 0;
  return sd < 0 && se > 0;
}

// The sign of a facet's projected area in an orthographic view, from the world:
// with screen x = r.p and y = u.p (plus constants, which cancel around the
// polygon), sum x_k y_k+1 - x_k+1 y_k = (r x u) . sum p_k x p_k+1, products of
// doubles, exact on binary floats (no gcd). Zero for the faces seen edge-on,
// which an axis view of a CAD part or a building is full of and which no
// filter can settle. (The screen's 2^k changes no sign.)
// (The polygon's n corners are input vertices id(k), none cut at a near plane.)
template <class Id>
int world_area_sign(const View& view, const Scene& scene, std::size_t n, Id&& id) {
  using M = CGAL::Mpzf;
  const auto &r = view.m[0], &u = view.m[1];
  const M nx = M(r[1]) * M(u[2]) - M(r[2]) * M(u[1]), ny = M(r[2]) * M(u[0]) - M(r[0]) * M(u[2]),
          nz = M(r[0]) * M(u[1]) - M(r[1]) * M(u[0]);
  M ax(0.0), ay(0.0), az(0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 &p = scene.vertices[static_cast<std::size_t>(id(k))], &q = scene.vertices[static_cast<std::size_t>(id((k + 1) % n))];
    ax = ax + (M(p.y) * M(q.z) - M(p.z) * M(q.y));
    ay = ay + (M(p.z) * M(q.x) - M(p.x) * M(q.z));
    az = az + (M(p.x) * M(q.y) - M(p.y) * M(q.x));
  }
  return (nx * ax + ny * ay + nz * az).sign();
}

// A facet's approximate screen centre (doubles: only orders depend on it).
std::array<double, 2> screen_centre(const WorldFacet& f, const Scene& scene, const View& view) {
  double sx = 0, sy = 0;
  for (auto id : f.v) {
    const Vec3& p = scene.vertices[id];
    auto row = [&](int r) { return view.m[r][0] * p.x + view.m[r][1] * p.y + view.m[r][2] * p.z + view.m[r][3]; };
    const double w = view.perspective ? row(3) : 1;
    sx += row(0) / w;
    sy += row(1) / w;
  }
  const double k = static_cast<double>(f.v.size());
  return {sx / k, sy / k};
}

}  // namespace

// Facets that walk the screen in their own order gain nothing in a lines-only
// drawing from a sort, which costs its own time (the 10^6-triangle terrain: the
// sort ~120 ms, and the edge matching and height fields ~65 ms more on the
// Morton order than on its rows; Intel Xeon 2.0 GHz). Told from 4096
// consecutive pairs spread evenly over the facets: their centres' median
// distance apart (L1) at most 3 times the spacing sqrt(A / n) of n facets
// spread evenly over A, the box of the middle 80 % of the samples' x and of
// their y, widened to 100 %. (The terrain's rows: 1.0 to 1.6 times, oblique or
// in perspective; a city's boxes in its blocks' order: 1.1; a subdivided
// elephant: 4.2; bunny00's facets: 31 to 38; a random order: 620 to 680.)
// Quantiles and a median, not the bounding box and the mean: a close-up in
// perspective throws the facets near the eye's plane thousands of widths
// away, which widened the box of bunny00's close-up until its facets seemed
// to walk the screen. Scenes under 2^16 facets are always sorted: their sort
// is cheap. The map does not depend on the facets' order, only the time and
// the counters.
bool walk_the_screen(const WorldFacets& wf, const Scene& scene, const View& view) {
  const std::size_t n = wf.facets.size();
  constexpr std::size_t kPairs = 4096;
  if (n < std::size_t{1} << 16) return false;
  std::vector<double> apart(kPairs), x(2 * kPairs), y(2 * kPairs);
  for (std::size_t j = 0; j < kPairs; ++j) {
    const std::size_t i = j * (n - 1) / kPairs;
    const std::array<double, 2> a = screen_centre(wf.facets[i], scene, view), b = screen_centre(wf.facets[i + 1], scene, view);
    if (!std::isfinite(a[0]) || !std::isfinite(a[1]) || !std::isfinite(b[0]) || !std::isfinite(b[1])) return false;
    apart[j] = std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]);
    x[2 * j] = a[0], x[2 * j + 1] = b[0], y[2 * j] = a[1], y[2 * j + 1] = b[1];
  }
  auto quantile = [](std::vector<double>& v, double q) {
    const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[static_cast<std::size_t>(k)];
  };
  const double area = (quantile(x, 0.9) - quantile(x, 0.1)) * (quantile(y, 0.9) - quantile(y, 0.1)) / 0.64;
  const double median = quantile(apart, 0.5);
  return area > 0 && median <= 3 * std::sqrt(area / static_cast<double>(n));
}

namespace {

// World facets in the Morton order of their approximate screen centres:
// order[k] is the facet that goes k-th. Everything built from them (edge
// pieces, screen facets, curves) then lies in memory roughly as on screen,
// and the later stages walk it in that order, without cache misses. Empty
// (the facets as they are) for a lines-only drawing whose facets walk the
// screen already (walk_the_screen): it looks only near its lines. (A whole
// map walks every cell's pieces, and gains more from the Morton order than
// the sort costs: the 10^6-triangle terrain's visibility and arrangement
// took ~0.5 s longer on its rows, against ~0.3 s saved before them.)
std::vector<std::uint32_t> screen_order(const WorldFacets& wf, const Scene& scene, const View& view, bool lines_only,
                                        int threads) {
  if (lines_only && walk_the_screen(wf, scene, view)) return {};
  const std::size_t n = wf.facets.size();
  std::vector<std::array<double, 2>> centre(n);
  // The centres and (per chunk, then together) their bounding box.
  const int size = 8192, chunks = chunk_count(static_cast<int>(n), size);
  std::vector<std::array<double, 4>> boxes(static_cast<std::size_t>(chunks), {HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL});
  parallel_chunks(static_cast<int>(n), size, threads, [&](int c, Chunk part) {
    double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;   // (stored once, below)
    for (auto i = static_cast<std::size_t>(part.begin); i < static_cast<std::size_t>(part.end); ++i) {
      centre[i] = screen_centre(wf.facets[i], scene, view);
      if (std::isfinite(centre[i][0]) && std::isfinite(centre[i][1])) {
        x0 = std::min(x0, centre[i][0]);
        x1 = std::max(x1, centre[i][0]);
        y0 = std::min(y0, centre[i][1]);
        y1 = std::max(y1, centre[i][1]);
      }
    }
    boxes[static_cast<std::size_t>(c)] = {x0, y0, x1, y1};
  });
  double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
  for (const auto& b : boxes) {
    x0 = std::min(x0, b[0]);
    y0 = std::min(y0, b[1]);
    x1 = std::max(x1, b[2]);
    y1 = std::max(y1, b[3]);
  }
  const double w = x1 > x0 ? x1 - x0 : 1, h = y1 > y0 ? y1 - y0 : 1;
  // The facets of one polygon (consecutive) share its first facet's key and so
  // keep their order: which of them speaks for the polygon where several hold
  // one edge (kinds, on fanned polygons) must not depend on the view.
  // (In chunks: a chunk's first facet takes its polygon's first facet's key.)
  std::vector<std::uint32_t> key(n);
  auto key_at = [&](std::size_t i) { return morton((centre[i][0] - x0) / w, (centre[i][1] - y0) / h); };
  parallel_chunks(static_cast<int>(n), size, threads, [&](int, Chunk part) {
    auto first = static_cast<std::size_t>(part.begin);
    while (first > 0 && wf.facets[first].face == wf.facets[first - 1].face) --first;
    std::uint32_t k = key_at(first);
    for (auto i = static_cast<std::size_t>(part.begin); i < static_cast<std::size_t>(part.end); ++i) {
      if (i > first && wf.facets[i].face != wf.facets[i - 1].face) k = key_at(i);
      key[i] = k;
    }
  });
  return order_by_key(key, threads);   // (ties by index: deterministic)
}

// The facets of `wf` in `order` (moved out of it), with their normals (an
// empty order: as they are).
void order_on_screen(WorldFacets& wf, const std::vector<std::uint32_t>& order, int threads) {
  if (order.empty()) return;
  std::vector<WorldFacet> facets;
  facets.reserve(order.size());
  fault_in_spare(facets, order.size(), threads);   // (its fresh pages, side by side)
  facets.resize(order.size());
  const bool normals = wf.normals.size() == wf.facets.size();
  std::vector<world::UnitNormal> normal(normals ? order.size() : 0);
  parallel_chunks(static_cast<int>(order.size()), 8192, threads, [&](int, Chunk r) {
    for (int k = r.begin; k < r.end; ++k) {
      const std::uint32_t f = order[static_cast<std::size_t>(k)];
      facets[static_cast<std::size_t>(k)] = std::move(wf.facets[f]);
      if (normals) normal[static_cast<std::size_t>(k)] = wf.normals[f];
    }
  });
  wf.facets = std::move(facets);
  wf.normals = std::move(normal);
}

// The world scene as a view orders its facets: the facets copied in `order`,
// the edge pieces renumbered (as matching them on those facets would give),
// the closed components by facet in that order.
struct InViewOrder {
  WorldFacets wf;
  std::vector<WorldPiece> pieces;
  ClosedComponents closed;
  std::vector<int> height_field;
};
InViewOrder in_view_order(const WorldScene& world, std::vector<std::uint32_t> order, int threads) {
  const std::size_t n = world.wf.facets.size();
  if (order.empty()) {   // (the world's own order)
    order.resize(n);
    std::iota(order.begin(), order.end(), 0u);
  }
  InViewOrder v;
  v.wf.degenerate = world.wf.degenerate;
  v.wf.nonplanar = world.wf.nonplanar;
  v.wf.nonconvex = world.wf.nonconvex;
  v.wf.facets.resize(n);
  const bool normals = world.wf.normals.size() == n;
  v.wf.normals.resize(normals ? n : 0);
  std::vector<std::uint32_t> new_index(n);
  parallel_chunks(static_cast<int>(n), 8192, threads, [&](int, Chunk r) {
    for (int k = r.begin; k < r.end; ++k) {
      const std::uint32_t f = order[static_cast<std::size_t>(k)];
      v.wf.facets[static_cast<std::size_t>(k)] = world.wf.facets[f];
      if (normals) v.wf.normals[static_cast<std::size_t>(k)] = world.wf.normals[f];
      new_index[f] = static_cast<std::uint32_t>(k);
    }
  });
  v.pieces = renumber_facets(world.edges, new_index, threads).pieces;
  // (Components keep their labels, facet numbers of the input order: only which
  // facets share one matters.)
  v.closed.component.resize(n);
  v.closed.side.resize(n);
  v.height_field.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    v.closed.component[k] = world.closed.component[order[k]];
    v.closed.side[k] = world.closed.side[order[k]];
    v.height_field[k] = world.height_field[order[k]];
  }
  return v;
}

}  // namespace

// Whether input vertex v lies in the plane of facet f, decided in world space
// (the projection keeps planes and incidences) on binary floats, with no gcd:
// det(q - o, r - o, v - o) for corners o, q, r of f that span its plane. False
// when f has no three such corners in the input (cut at the near plane).
bool in_world_plane(const std::vector<Vec3>& input, long v, const Facet& f) {
  auto at = [&](long id) -> const Vec3& { return input[static_cast<std::size_t>(id)]; };
  const std::size_t m = f.id.size();
  std::size_t k0 = 0;
  while (k0 < m && f.id[k0] < 0) ++k0;
  for (std::size_t k = k0 + 1; k + 1 < m; ++k) {
    if (f.id[k] < 0 || f.id[k + 1] < 0) continue;
    const Vec3 &o = at(f.id[k0]), &q = at(f.id[k]), &r = at(f.id[k + 1]);
    if (world::collinear(o, q, r)) continue;
    return world::orientation(o, q, r, at(v)) == 0;
  }
  return false;
}

std::vector<SmallInts> faces_lists(const std::vector<Curve>& curves, int threads) {
  std::vector<SmallInts> out(curves.size());
  parallel_chunks(static_cast<int>(curves.size()), 8192, threads, [&](int, Chunk r) {
    for (int i = r.begin; i < r.end; ++i) out[static_cast<std::size_t>(i)] = curves[static_cast<std::size_t>(i)].faces;
  });
  return out;
}

FT depth_on(const Curve& c, const P2& p) { return depth_along(*c.s, *c.t, p); }

Curve intersection_curve(const P3& s, const P3& t, int fa, int fb, int face_a, int face_b, std::deque<P3>& ends) {
  Curve c;
  c.s = &ends.emplace_back(s);
  c.t = &ends.emplace_back(t);
  c.sharers = {fa, fb};
  c.sharer_edge = {-1, -1};
  c.faces = {std::min(face_a, face_b), std::max(face_a, face_b)};
  c.kind = EdgeKind::Intersection;
  c.drawn = true;
  c.order_face = c.faces[0];
  c.box = box_of(s) + box_of(t);
  return c;
}

// What making a curve from an edge piece needs: the world facets and pieces, the
// used vertices' images, the near plane's cuts. Shared with the screen scene
// while curves are latent (make_latent_curves), freed with it otherwise.
struct CurveMaker {
  const Scene* scene = nullptr;
  const View* view = nullptr;
  int k = 0;                     // the screen scale
  double cos_crease = 1;
  bool smooth = false;
  bool drop_inside_edge_on = false;   // (the visible map's curves: inside_edge_on_plane)
  // Orthographic: +1 or -1 where toward_eye (r x u) points towards the eye
  // (r, u the view's first two rows: points share an image along r x u, and
  // depth falls that way); 0 in perspective.
  int toward_eye = 0;
  Vec3 row(int k) const { return {view->m[k][0], view->m[k][1], view->m[k][2]}; }
  WorldFacets wf;
  std::vector<WorldPiece> pieces;
  std::vector<std::uint32_t> used;    // place -> input index: vertices in the order facets first use them
  std::vector<std::uint32_t> local;   // input index -> place in used
  const P3* sv = nullptr;             // images, by place (the screen scene's table)
  const ImageBounds* bounds = nullptr;   // their intervals, by place, where they are left for later
  const char* bounds_made = nullptr;     // which of those are made, where only some are (sparse)
  std::vector<char> front;            // in front of the near plane, by place
  bool all_front = false;             // every vertex is (in_front then reads nothing)
  const ExactSource* exact = nullptr;   // (the screen scene's)
  std::vector<std::vector<P3>> clip_edges;   // per facet: its cut by the near plane (perspective only)
  bool cut(int facet) const { return !clip_edges.empty() && !clip_edges[static_cast<std::size_t>(facet)].empty(); }
  // Per facet, what make() and judge() ask of it, side by side in 8 bytes (a
  // facet is 144 bytes, a world facet 48: its sharers' facets were most of their
  // cache misses): its facing, whether it has corners (not culled before
  // projection or by the near plane), whether it hides and labels (as culling
  // left it), its face, and which of its edges are its face's boundary.
  struct Look {
    Facing facing = Facing::EdgeOn;
    bool projected = false;
    bool occluder = false;
    // Bit k: edge k is EdgeRole::Boundary (k < kEdgeBits); kMany: the facet
    // has more edges (its WorldFacet tells).
    std::uint8_t boundary = 0;
    int face = -1;
    static constexpr std::size_t kEdgeBits = 7;
    static constexpr std::uint8_t kMany = 1u << kEdgeBits;
  };
  std::vector<Look> look;
  static Look look_of(const FacetBrief& f, const WorldFacet& w) {
    Look l{f.facing, f.projected, f.occluder, 0, w.face};
    if (w.role.size() > Look::kEdgeBits) {
      l.boundary = Look::kMany;
      return l;
    }
    for (std::size_t k = 0; k < w.role.size(); ++k)
      if (w.role[k] == EdgeRole::Boundary) l.boundary |= static_cast<std::uint8_t>(1u << k);
    return l;
  }
  // Whether the sharer's edge is its face's boundary (not a diagonal inside it).
  bool on_boundary(const Sharer& s) const {
    const Look& l = look[static_cast<std::size_t>(s.facet)];
    if (l.boundary & Look::kMany)
      return wf.facets[static_cast<std::size_t>(s.facet)].role[s.edge] == EdgeRole::Boundary;
    return (l.boundary >> s.edge) & 1u;
  }
  int face_of(int facet) const { return look[static_cast<std::size_t>(facet)].face; }
  Facing facing(int facet) const {   // (a facet without corners: edge-on)
    const Look& l = look[static_cast<std::size_t>(facet)];
    return l.projected ? l.facing : Facing::EdgeOn;
  }

  bool in_front(std::uint32_t id) const { return all_front || front[local[id]] != 0; }
  const P3& image(std::uint32_t id) const { return sv[local[id]]; }
  // The image of the vertex at place u (in front of the near plane), made now.
  P3 make_image(std::uint32_t u) const;
  // Its intervals, as the image made would have them.
  // (Never inlined: every interval read may call it, where the intervals are
  // made only where asked; inlined there, GCC took 25 minutes on this file.)
  [[gnu::noinline]] ImageBounds bounds_of(std::uint32_t u) const;
  // Asks for the input vertex a few places after place u, ahead of its use: the
  // places are in screen order, not the input's, and each place's vertex was a
  // cache miss (a 10^6-triangle terrain's image bounds: 63-65 -> 56-60 ms).
  void fetch_after(std::size_t u) const {
    constexpr std::size_t ahead = 16;
    if (u + ahead < used.size()) __builtin_prefetch(&scene->vertices[used[u + ahead]]);
  }
  // The box of vertex id's image (its kept intervals where it is left for later).
  CGAL::Bbox_2 image_box(std::uint32_t id) const {
    return bounds ? box_of(bounds_at(local[id])) : box_of(image(id));
  }
  // The intervals at place u, kept or (not made yet) computed now.
  ImageBounds bounds_at(std::uint32_t u) const { return !bounds_made || bounds_made[u] ? bounds[u] : bounds_of(u); }
  // Whether vertices a and b (in front) have one image on the screen, exactly.
  bool same_image(std::uint32_t a, std::uint32_t b) const;
  WorldPoint world(std::uint32_t id) const {
    const Vec3& p = scene->vertices[id];
    return WorldPoint{FT(p.x), FT(p.y), FT(p.z)};
  }
  P3 near_image(const WorldPoint& w) const {   // a point on the near plane: depth 0 exactly
    Homogeneous h = transform(*view, w.x, w.y, w.z);
    mpq_class x = to_mpq(h.X / h.W), y = to_mpq(h.Y / h.W);
    times_pow2(x, k);
    times_pow2(y, k);
    return P3{from_mpq(x), from_mpq(y), FT(0)};
  }
  // Where edge a-b (a in front) crosses the near plane Z = 0 (homogeneous Z made
  // for the two ends here: few edges are cut, and a lazy number per vertex would
  // be 80 bytes).
  P3 clip_point(std::uint32_t a, std::uint32_t b) const {
    if (const P3* known = known_clip(a, b)) return *known;
    return near_image(
        cut_at_near(world(a), world(b), projected_number(*exact, a, 2, false), projected_number(*exact, b, 2, false)));
  }
  // The cut points of the facets' edges, each made once (make_clips): the two
  // facets of an edge and its curve share one point, so that the curves meeting
  // there (the edge's, the facets' near-plane cuts) know it by identity (GMP made
  // it; comparing equal values would take it again), by key (lower id, higher id).
  std::vector<std::pair<std::uint64_t, P3>> clips;
  static std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
    return a < b ? (std::uint64_t{a} << 32) | b : (std::uint64_t{b} << 32) | a;
  }
  const P3* known_clip(std::uint32_t a, std::uint32_t b) const {
    const std::uint64_t key = edge_key(a, b);
    const auto it = std::lower_bound(clips.begin(), clips.end(), key,
                                     [](const std::pair<std::uint64_t, P3>& c, std::uint64_t k) { return c.first < k; });
    return it != clips.end() && it->first == key ? &it->second : nullptr;
  }
  void make_clips(int threads);
  // Pieces make() drops, counted by why: hidden, clipped, seen end-on, inside a
  // plane seen edge-on.
  using Dropped = std::array<std::int64_t, 4>;
  bool make(const WorldPiece& wp, Curve& c, Dropped& dropped, std::deque<P3>& ends) const;
  // What make() would do with a piece, without making its curve: a lines-only
  // drawing leaves most pieces latent (only their numbers kept).
  enum class Verdict { Hidden, Clipped, EndOn, InPlane, Drawn, Latent };   // (the first four: Dropped's order)
  Verdict judge(const WorldPiece& wp) const;
  // A latent piece's box, as its curve would have it: its ends' images, or the
  // near plane's cut points (made by make_clips: looked up).
  CGAL::Bbox_2 latent_box(const WorldPiece& wp) const {
    const bool fa = in_front(wp.a), fb = in_front(wp.b);
    if (fa && fb) return image_box(wp.a) + image_box(wp.b);
    return (fa ? image_box(wp.a) : box_of(clip_point(wp.b, wp.a))) + (fb ? image_box(wp.b) : box_of(clip_point(wp.a, wp.b)));
  }

 private:
  // make()'s steps, shared with judge().
  bool any_occluder(const WorldPiece& wp) const;
  void faces_of(const WorldPiece& wp, SmallInts& faces, std::array<int, 2>& facet) const;
  EdgeKind kind_of(const SmallInts& faces, const std::array<int, 2>& facet) const;
  Spanning spanning(int facet) const;
  bool creased(int f, int g) const;
  bool drawn_of(const SmallInts& faces, EdgeKind kind) const { return !faces.empty() && (kind != EdgeKind::Smooth || smooth); }
  bool covered(const WorldPiece& wp) const;
  bool seen_with_area(const WorldPiece& wp) const;
  bool inside_edge_on_plane(const WorldPiece& wp) const;
  // Whether the facet is its face's only one: every edge of it on the face's
  // boundary (none a fan's or a triangulation's diagonal).
  bool whole(int facet) const {
    const Look& l = look[static_cast<std::size_t>(facet)];
    const WorldFacet& w = wf.facets[static_cast<std::size_t>(facet)];
    if (l.boundary & Look::kMany)
      return std::all_of(w.role.begin(), w.role.end(), [](EdgeRole r) { return r == EdgeRole::Boundary; });
    return l.boundary == (1u << w.role.size()) - 1;
  }
};

// Whether some facet sharing the piece hides or labels: else every one is a
// culled back face, and the piece is hidden (or coincident with a nearer
// visible line on screen): it cannot change the map.
bool CurveMaker::any_occluder(const WorldPiece& wp) const {
  for (const Sharer& s : wp.sharers) {
    const Look& f = look[static_cast<std::size_t>(s.facet)];
    if (f.occluder || (f.projected && f.facing == Facing::EdgeOn)) return true;
  }
  return false;
}

// Whether some facet sharing the piece is seen with area (facing the eye or
// away from it, exactly): then its plane is not seen edge-on, so that two of
// its points never have one image, and the piece, two distinct points of it
// (its ends), is not seen end-on: no need to compare its ends' images.
bool CurveMaker::seen_with_area(const WorldPiece& wp) const {
  return std::any_of(wp.sharers.begin(), wp.sharers.end(),
                     [&](const Sharer& s) { return facing(s.facet) != Facing::EdgeOn; });
}

// Whether an occluder lies on each side of the piece on screen: two sharers,
// both occluders, on opposite sides. Each is convex and lies left of its edges
// where it turns counter-clockwise on screen (Front), right where clockwise
// (Back); `forward` says which way it runs along the piece. Combinatorial: no
// predicate.
bool CurveMaker::covered(const WorldPiece& wp) const {
  if (wp.sharers.size() != 2 || wp.sharers[0].facet == wp.sharers[1].facet) return false;
  const Sharer &a = wp.sharers[0], &b = wp.sharers[1];
  const Look &fa = look[static_cast<std::size_t>(a.facet)], &fb = look[static_cast<std::size_t>(b.facet)];
  if (!fa.occluder || !fb.occluder) return false;
  return (a.forward != b.forward) == (fa.facing == fb.facing);
}

// Whether the piece lies inside a plane seen edge-on, behind the facet of it
// that a line of sight meets first (the visible map's curves only): no facet
// sharing it hides or labels, and one that is seen edge-on, projected and not
// cut by the near plane lies on the eye's side of it (orthographic: towards the
// eye along the lines of sight; in perspective, where that side is not sought:
// two such facets on opposite sides of it, the mesh going on across it). A line
// of sight in that facet's plane through the piece then entered the facet
// before, nearer, through the edge where it entered, a piece that is kept (of
// the plane's outline, or one beside a facet the near plane cuts) or again one
// like this, nearer each time. That nearer kept piece is visible wherever this
// one is (a face that hides it hides this one: edge-on facets hide nothing, and
// the nearer piece's other facets have it on their outline), so this one, drawn
// or not, is never the first of the pieces there; and it bounds no region (no
// facet of it labels). Every facet of it is a whole face (no diagonal inside a
// polygon): the edge the line of sight came in by is then a line of that face,
// which competes (a diagonal does not), and no other facet of the same face,
// not seen edge-on, can hide the nearer piece and not this one (a fanned
// non-planar polygon's). It cannot change the map. (A CAD model in a sheet view:
// the triangles of each plane seen edge-on, whose edges all lie on one line
// there, pairwise overlapping; the far edges of boxes seen along an axis, on
// the lines of their near edges.) Exact: filtered world predicates.
bool CurveMaker::inside_edge_on_plane(const WorldPiece& wp) const {
  if (!drop_inside_edge_on) return false;
  for (const Sharer& s : wp.sharers)
    if (look[static_cast<std::size_t>(s.facet)].occluder || !whole(s.facet)) return false;
  auto flat = [&](const Sharer& s) {   // (seen edge-on, projected, not cut)
    const Look& f = look[static_cast<std::size_t>(s.facet)];
    return f.projected && f.facing == Facing::EdgeOn && !cut(s.facet);
  };
  // A corner of the facet off the piece's line (convex: the facet lies on its
  // side), the one after the shared edge; on the line (a straight turn): 0 below.
  auto beyond = [&](const Sharer& s) -> const Vec3& {
    const auto& v = wf.facets[static_cast<std::size_t>(s.facet)].v;
    return scene->vertices[v[(s.edge + 2) % v.size()]];
  };
  const Vec3 &p = scene->vertices[wp.a], &q = scene->vertices[wp.b];
  if (toward_eye != 0)
    return std::any_of(wp.sharers.begin(), wp.sharers.end(), [&](const Sharer& s) {
      return flat(s) && toward_eye * world::side_of_line_toward(p, q, beyond(s), row(0), row(1)) > 0;
    });
  if (wp.sharers.size() != 2 || wp.sharers[0].facet == wp.sharers[1].facet) return false;
  if (!flat(wp.sharers[0]) || !flat(wp.sharers[1])) return false;
  return world::same_side_of_line(p, q, beyond(wp.sharers[0]), beyond(wp.sharers[1])) < 0;
}

// The faces whose boundary the piece is (a sharer's edge that is not a
// diagonal inside its polygon), ascending, each once; where there are two, a
// facet of each (its first sharer with that face), for kind_of.
void CurveMaker::faces_of(const WorldPiece& wp, SmallInts& faces, std::array<int, 2>& facet) const {
  faces.clear();
  facet = {-1, -1};
  if (wp.sharers.size() <= 2) {   // (most pieces: no sort)
    for (const Sharer& s : wp.sharers) {
      if (!on_boundary(s)) continue;
      const int face = face_of(s.facet);
      if (faces.empty()) { faces.push_back(face); facet[0] = s.facet; }
      else if (face != faces[0]) { faces.push_back(face); facet[1] = s.facet; }
    }
    if (faces.size() == 2 && faces[1] < faces[0]) {
      std::swap(faces[0], faces[1]);
      std::swap(facet[0], facet[1]);
    }
    return;
  }
  for (const Sharer& s : wp.sharers)
    if (on_boundary(s)) faces.push_back(face_of(s.facet));
  std::sort(faces.begin(), faces.end());
  faces.truncate(static_cast<std::size_t>(std::unique(faces.begin(), faces.end()) - faces.begin()));
  if (faces.size() != 2) return;
  for (const Sharer& s : wp.sharers) {
    if (!on_boundary(s)) continue;
    for (std::size_t k = 0; k < 2; ++k)
      if (face_of(s.facet) == faces[k] && facet[k] < 0) facet[k] = s.facet;
  }
}

// A facet's spanning corners: those projection found (ExactSource::spanning:
// every projected facet not parallel to the screen), else found again.
Spanning CurveMaker::spanning(int facet) const {
  std::array<std::uint32_t, 3> ids = exact->spanning[static_cast<std::size_t>(facet)];
  if (ids[0] == 0 && ids[1] == 0 && ids[2] == 0) ids = spanning_ids(*scene, wf.facets[static_cast<std::size_t>(facet)]);
  return {scene->vertices[ids[0]], scene->vertices[ids[1]], scene->vertices[ids[2]]};
}

// The piece's kind, from the faces sharing it and a facet of each (faces_of).
EdgeKind CurveMaker::kind_of(const SmallInts& faces, const std::array<int, 2>& facet) const {
  if (faces.size() >= 3) return EdgeKind::Crease;
  if (faces.size() != 2) return EdgeKind::Border;
  const Facing ga = facing(facet[0]), gb = facing(facet[1]);
  if ((ga == Facing::Front) != (gb == Facing::Front)) return EdgeKind::Silhouette;
  if (ga == gb && ga != Facing::EdgeOn) return creased(facet[0], facet[1]) ? EdgeKind::Crease : EdgeKind::Smooth;
  return EdgeKind::Smooth;
}

// Whether facets f and g meet at a crease: from their normals' estimates where
// they tell (most edges), else from their spanning corners, exactly.
bool CurveMaker::creased(int f, int g) const {
  if (wf.normals.size() == wf.facets.size())
    if (const std::optional<bool> told = world::crease_from_normals(wf.normals[static_cast<std::size_t>(f)],
                                                                   wf.normals[static_cast<std::size_t>(g)], cos_crease))
      return *told;
  return is_crease(spanning(f), spanning(g), cos_crease);
}

// The curve of edge piece wp, made in c (every field set: c may be reused);
// false if it is dropped (counted in `dropped`: hidden, clipped, seen end-on,
// inside a plane seen edge-on).
// An end cut at the near plane is kept in `ends`.
bool CurveMaker::make(const WorldPiece& wp, Curve& c, Dropped& dropped, std::deque<P3>& ends) const {
  std::int64_t &dropped_hidden = dropped[0], &dropped_clipped = dropped[1], &dropped_point = dropped[2];
  c.sharers.clear();
  c.sharer_edge.clear();
  auto front = [this](std::uint32_t id) { return in_front(id); };
  for (const Sharer& s : wp.sharers) {
    c.sharers.push_back(s.facet);
    // A facet not cut at the near plane keeps its vertices: its edge k is the
    // world's; a cut one's polygon numbers its edges anew.
    const Look& f = look[static_cast<std::size_t>(s.facet)];
    c.sharer_edge.push_back(!f.projected     ? -1
                            : !cut(s.facet) ? s.edge
                                            : screen_edge_of(wf.facets[s.facet].v, s.edge, front));
  }
  if (!any_occluder(wp)) { ++dropped_hidden; return false; }
  if (inside_edge_on_plane(wp)) { ++dropped[3]; return false; }
  std::array<int, 2> facet;
  faces_of(wp, c.faces, facet);
  c.kind = kind_of(c.faces, facet);
  c.drawn = drawn_of(c.faces, c.kind);
  c.covered = covered(wp);
  // Its place in the (depth, face index) order: the lowest face it belongs to.
  c.order_face = face_of(c.sharers[0]);
  for (int s : c.sharers) c.order_face = std::min(c.order_face, face_of(s));
  if (!c.faces.empty()) c.order_face = c.faces[0];
  // Clip at the near plane, project.
  std::uint32_t a = wp.a, b = wp.b;
  const bool fa = in_front(a), fb = in_front(b);
  if (!fa && !fb) { ++dropped_clipped; return false; }
  c.s = fa ? &image(a) : &ends.emplace_back(clip_point(b, a));
  c.t = fb ? &image(b) : &ends.emplace_back(clip_point(a, b));
  c.vs = fa ? static_cast<VertexId>(a) : -1;
  c.vt = fb ? static_cast<VertexId>(b) : -1;
  if (!seen_with_area(wp) && equal_points(c.s->xy(), c.t->xy())) { ++dropped_point; return false; }   // seen end-on
  c.box = box_of(*c.s) + box_of(*c.t);
  return true;
}

// As make() decides, in the same order. (A cut end's point is one make_clips
// made: looked up, not kept.)
CurveMaker::Verdict CurveMaker::judge(const WorldPiece& wp) const {
  if (!any_occluder(wp)) return Verdict::Hidden;
  if (inside_edge_on_plane(wp)) return Verdict::InPlane;
  SmallInts faces;
  std::array<int, 2> facet;
  faces_of(wp, faces, facet);
  if (drawn_of(faces, kind_of(faces, facet))) return Verdict::Drawn;
  const bool fa = in_front(wp.a), fb = in_front(wp.b);
  if (!fa && !fb) return Verdict::Clipped;
  if (seen_with_area(wp)) return Verdict::Latent;
  if (fa && fb) {
    if (same_image(wp.a, wp.b)) return Verdict::EndOn;
  } else {
    const P3 s = fa ? image(wp.a) : clip_point(wp.b, wp.a), t = fb ? image(wp.b) : clip_point(wp.a, wp.b);
    if (equal_points(s.xy(), t.xy())) return Verdict::EndOn;
  }
  return Verdict::Latent;
}

P3 CurveMaker::make_image(std::uint32_t u) const {
  const std::uint32_t id = used[u];
  if (!view->perspective) {
    // Each coordinate is a double where it is one exactly, else a lazy leaf:
    // its interval now, its rational only if ever needed.
    const Vec3& p = scene->vertices[id];
    auto coordinate = [&](int r) {
      double d;
      return exact_in_doubles(view->m[r], p, d) ? scaled(d, k) : projected_number(*exact, id, r, true);
    };
    return P3{coordinate(0), coordinate(1), coordinate(2)};
  }
  // Perspective: X/W, Y/W, Z/W as lazy leaves (the quotient's interval now;
  // W's, which the three share, found once).
#ifdef VISMAP_FLOAT_KERNEL
  return P3{perspective_number(*exact, id, 0), perspective_number(*exact, id, 1), perspective_number(*exact, id, 2)};
#else
  const std::array<Interval, 3> q = perspective_intervals(*exact, id, w_interval(*exact, id));
  return P3{perspective_number(*exact, id, 0, q[0]), perspective_number(*exact, id, 1, q[1]),
            perspective_number(*exact, id, 2, q[2])};
#endif
}

ImageBounds CurveMaker::bounds_of(std::uint32_t u) const {
#ifdef VISMAP_FLOAT_KERNEL
  const P3 image = make_image(u);
  return {approx_of(image.x), approx_of(image.y), approx_of(image.z)};
#else
  const std::uint32_t id = used[u];
  ImageBounds b;
  Interval* out[3] = {&b.x, &b.y, &b.z};
  const Vec3& p = scene->vertices[id];
  if (view->perspective) {
    const std::array<Interval, 3> q = perspective_intervals(*exact, id, w_interval(*exact, id));
    b = {q[0], q[1], q[2]};
  } else {
    for (int r = 0; r < 3; ++r) {
      double d;
      *out[r] = exact_in_doubles(view->m[r], p, d) ? scaled_interval(d, k) : projected_interval(*exact, id, r, true);
    }
  }
  // (An unbounded interval: the point made exact at once, as steady_point
  // does, which narrows the coordinates' intervals. The image's own, then.)
  if (!steady_detail::bounded(b.x) || !steady_detail::bounded(b.y)) {
    const P3 image = make_image(u);
    b = {approx_of(image.x), approx_of(image.y), approx_of(image.z)};
  }
  return b;
#endif
}

bool CurveMaker::same_image(std::uint32_t a, std::uint32_t b) const {
  if (!bounds) return equal_points(image(a).xy(), image(b).xy());
  // (As equal_points: apart intervals tell, uncounted; else the two points,
  // made for the question, compared as the images would be.)
  const ImageBounds p = bounds_at(local[a]), q = bounds_at(local[b]);
  auto apart = [](const Interval& i, const Interval& j) { return i.sup() < j.inf() || j.sup() < i.inf(); };
  if (apart(p.x, q.x) || apart(p.y, q.y)) return false;
  return equal_points(make_image(local[a]).xy(), make_image(local[b]).xy());
}

namespace {
// (Sparse scenes: the intervals of the images at places, made where not yet.)
void make_bounds_of(const CurveMaker& M, ScreenScene& ss, const std::vector<std::uint32_t>& places, int threads);

// The images at `places` (any order, repeats allowed) that are not made yet,
// made in parallel, each on one thread, in the order of their places.
void make_images_of(const CurveMaker& M, ImageTable& images, const std::vector<std::uint32_t>& places, int threads) {
  std::vector<char> wanted(images.size(), 0);
  for (const std::uint32_t u : places) wanted[u] = !images.made(u);
  std::vector<std::uint32_t> make;
  for (std::size_t u = 0; u < wanted.size(); ++u)
    if (wanted[u]) make.push_back(static_cast<std::uint32_t>(u));
  parallel_chunks(static_cast<int>(make.size()), 1024, threads, [&](int, Chunk r) {
    for (int i = r.begin; i < r.end; ++i) {
      const std::uint32_t u = make[static_cast<std::size_t>(i)];
      images.make(u, M.make_image(u));
    }
  });
}
}  // namespace

// Every facet edge the near plane cuts, its cut point (made in parallel).
void CurveMaker::make_clips(int threads) {
  if (std::all_of(front.begin(), front.end(), [](char f) { return f != 0; })) return;   // (nothing is cut)
  std::vector<std::pair<std::uint32_t, std::uint32_t>> cut;   // (in front, behind)
  for (const WorldFacet& w : wf.facets)
    for (std::size_t k = 0, n = w.v.size(); k < n; ++k) {
      const std::uint32_t a = w.v[k], b = w.v[(k + 1) % n];
      if (in_front(a) && !in_front(b)) cut.emplace_back(a, b);
      else if (in_front(b) && !in_front(a)) cut.emplace_back(b, a);
    }
  std::sort(cut.begin(), cut.end(), [](const auto& x, const auto& y) { return edge_key(x.first, x.second) < edge_key(y.first, y.second); });
  cut.erase(std::unique(cut.begin(), cut.end()), cut.end());
  clips = parallel_make<std::pair<std::uint64_t, P3>>(static_cast<int>(cut.size()), 256, threads, [&](int, int i, auto& c) {
    const auto [a, b] = cut[static_cast<std::size_t>(i)];
    c = {edge_key(a, b), clip_point(a, b)};
  });
}

DepthPlane DepthPlane::of_doubles(double a, double b, double c) {
  DepthPlane p;
  p.approx_ = {Interval(a), Interval(b), Interval(c)};
  return p;
}

DepthPlane DepthPlane::of_source(const Interval& a, const Interval& b, const Interval& c, const ExactSource& source,
                                 std::uint32_t facet) {
  DepthPlane p;
  p.approx_ = {a, b, c};
  p.source_ = &source;
  p.facet_ = facet;
  return p;
}

DepthPlane DepthPlane::of_rationals(const mpq_class& a, const mpq_class& b, const mpq_class& c,
                                    const ExactSource& source, std::uint32_t facet) {
  DepthPlane p;
  const std::array<const mpq_class*, 3> abc{&a, &b, &c};
  for (std::size_t k = 0; k < 3; ++k) {
    const std::pair<double, double> i = CGAL::to_interval(*abc[k]);
    p.approx_[k] = Interval(i.first, i.second);
  }
  p.source_ = &source;
  p.facet_ = facet;
  source.planes[facet].store(new std::array<mpq_class, 3>{a, b, c});   // (as if asked for: plane_of)
  return p;
}

std::array<mpq_class, 3> DepthPlane::exact() const {
#ifndef VISMAP_FLOAT_KERNEL
  if (source_) return source_->plane_of(facet_);
#endif
  return {mpq_class(approx_[0].inf()), mpq_class(approx_[1].inf()), mpq_class(approx_[2].inf())};
}

FT DepthPlane::number(int k) const {
  const auto i = static_cast<std::size_t>(k);
  if (!source_ || approx_[i].is_point()) return FT(approx_[i].inf());
#ifdef VISMAP_FLOAT_KERNEL
  return FT(approx_[i].inf());
#else
  return FT(new PlaneRep(approx_[i], *source_, facet_, k));
#endif
}

bool DepthPlane::operator==(const DepthPlane& o) const {
  for (std::size_t k = 0; k < 3; ++k)   // (intervals apart: different planes)
    if (approx_[k].sup() < o.approx_[k].inf() || o.approx_[k].sup() < approx_[k].inf()) return false;
  return exact() == o.exact();
}

namespace {

// The near plane's cut through closed components, on the screen, and the
// components whose cut it cannot list (a vertex on the plane: the cut passes
// through corners; a facet cut other than in two points).
struct NearCut {
  std::vector<CutSegment> segments;
  std::vector<char> unlisted;   // per component
};
NearCut near_cut(const ScreenScene& ss, const CurveMaker& M, const std::vector<std::int8_t>& zsign,
                 const ClosedComponents& cc) {
  NearCut cut;
  cut.unlisted.assign(ss.facet_count(), 0);
  for (std::size_t fi = 0; fi < ss.facet_count(); ++fi) {
    if (cc.side[fi] == 0) continue;
    const int c = cc.component[fi];
    for (auto id : M.wf.facets[fi].v)
      if (zsign[M.local[id]] == 0) cut.unlisted[static_cast<std::size_t>(c)] = 1;
    const auto& ce = M.clip_edges[fi];
    if (ce.size() == 2) cut.segments.push_back({c, ce[0].xy(), ce[1].xy(), box_of(ce[0]) + box_of(ce[1])});
    else if (!ce.empty()) cut.unlisted[static_cast<std::size_t>(c)] = 1;
  }
  return cut;
}

// Closed components hide their own faces (engine/culling.h, engine/cap_inside.h):
// where every ray towards a facet starts outside the solid (its image apart from
// the caps of the near plane's cut: their boxes apart, or else its image outside
// every cap, exactly), the facets seen from behind; where every one starts inside
// (its image within a cap), the facets seen from the front. They stop being
// occluders (counted).
void cull_by_closed_solids(ScreenScene& ss, const CurveMaker& M, const View& view, const std::vector<std::int8_t>& zsign,
                           const ClosedComponents& cc, int threads, Stats& stats) {
  const std::size_t n = ss.facet_count();
  // (No closed component, an open surface: nothing to cull, nor any per-facet
  // box or cap list to make; on a 10^6-triangle terrain those were ~60 MB.)
  if (std::all_of(cc.side.begin(), cc.side.end(), [](std::int8_t s) { return s == 0; })) {
    stats.count("culled_back_faces", 0);
    stats.count("culled_front_faces_in_caps", 0);
    stats.count("near_plane_caps", 0);
    return;
  }
  std::vector<NearCap> caps;
  if (view.perspective) {
    NearPlane np;
    np.z_sign = [&](std::uint32_t id) { return static_cast<int>(zsign[M.local[id]]); };
    np.facet_cut = [&](int fi, CGAL::Bbox_2& b) {
      const auto& ce = M.clip_edges[static_cast<std::size_t>(fi)];
      if (ce.size() != 2) return false;
      b = box_of(ce[0]) + box_of(ce[1]);
      return true;
    };
    np.on_plane = [&](std::uint32_t id) { return box_of(M.near_image(M.world(id))); };
    caps = near_caps(M.wf, M.pieces, cc, np);
  }
  const int nf = static_cast<int>(n);
  std::vector<CGAL::Bbox_2> facet_box(n);
  parallel_chunks(nf, 16384, threads, [&](int, Chunk r) {
    for (int fi = r.begin; fi < r.end; ++fi) facet_box[static_cast<std::size_t>(fi)] = ss.brief(static_cast<std::size_t>(fi)).box;
  });
  const std::vector<char> hidden_back = hidden_when_back_facing(cc, caps, facet_box, threads);
  // Seen from the solid's outside (the front of an outward-oriented component's
  // face, the back of an inward-oriented one's): hidden where every ray towards
  // it starts inside a cap (only a perspective view's near plane cuts).
  auto seen_from_outside = [&](std::size_t fi) {
    const FacetBrief& f = ss.brief(fi);
    return (cc.side[fi] > 0 && f.facing == Facing::Front) || (cc.side[fi] < 0 && f.facing == Facing::Back);
  };
  std::vector<std::int8_t> cap_side(n, 0);   // (cap_sides: +1 inside a cap, -1 outside them all)
  if (!caps.empty()) {
    // Where their boxes do not tell: each facet's image against the caps, exactly
    // (a facet seen from behind whose box meets a cap's box may still lie
    // outside every cap: a near plane through a mesh's sides makes caps whose
    // images reach far across the screen).
    const NearCut cut = near_cut(ss, M, zsign, cc);
    std::vector<char> candidate(n, 0);
    std::vector<const P2*> point(n, nullptr);
    parallel_chunks(nf, 16384, threads, [&](int, Chunk r) {
      for (auto fi = static_cast<std::size_t>(r.begin); fi < static_cast<std::size_t>(r.end); ++fi) {
        if (!ss.brief(fi).occluder || cc.side[fi] == 0 || cut.unlisted[static_cast<std::size_t>(cc.component[fi])] ||
            (!seen_from_outside(fi) && hidden_back[fi]))
          continue;
        candidate[fi] = 1;
        point[fi] = &ss.facet(fi).v[0].xy();
      }
    });
    cap_side = cap_sides(cc, cut.segments, candidate, facet_box, point, threads);
  }
  // What is culled, counted per chunk (back, front). (Such a component is also a
  // solid, whose facets never pierce each other: solid_labels.)
  std::vector<ChunkCounts> culled(static_cast<std::size_t>(chunk_count(nf, 16384)));
  parallel_chunks(nf, 16384, threads, [&](int k, Chunk r) {
    auto& [back, front] = culled[static_cast<std::size_t>(k)];
    for (auto fi = static_cast<std::size_t>(r.begin); fi < static_cast<std::size_t>(r.end); ++fi) {
      if (!ss.brief(fi).occluder || cc.side[fi] == 0) continue;
      if (seen_from_outside(fi)) {
        if (cap_side[fi] <= 0) continue;
        ss.set_occluder(fi, false);
        ++front;
      } else if (hidden_back[fi] || cap_side[fi] < 0) {
        ss.set_occluder(fi, false);
        ++back;
      }
    }
  });
  const auto [back, front] = summed(culled);
  stats.count("culled_back_faces", back);
  stats.count("culled_front_faces_in_caps", front);
  stats.count("near_plane_caps", static_cast<std::int64_t>(caps.size()));
}

// Per facet: its solid (ScreenScene::solid), where it is known not to meet
// itself: a closed component that closed_components took as such (side != 0),
// or an open surface that is a graph over a coordinate plane (`height_field`:
// engine/height_fields.h), whose label wins. Else -1. Camera-free.
std::vector<int> solid_labels(const ClosedComponents& cc, const std::vector<int>& height_field, std::size_t n) {
  std::vector<int> solid(n, -1);
  for (std::size_t fi = 0; fi < n; ++fi) {
    if (fi < cc.side.size() && cc.side[fi] != 0) solid[fi] = cc.component[fi];
    if (fi < height_field.size() && height_field[fi] >= 0) solid[fi] = height_field[fi];
  }
  return solid;
}

// The box of a polygon's n corners, corner(k), from their intervals.
template <class Corner>
CGAL::Bbox_2 corners_box(const ScreenScene& ss, std::size_t n, Corner&& corner) {
  CGAL::Bbox_2 box = box_at(ss, corner(0));
  for (std::size_t k = 1; k < n; ++k) box += box_at(ss, corner(k));
  return box;
}

// A facet's box and depth range (zlo, zhi), from its corners' intervals.
void bound(const ScreenScene& ss, Facet& f) {
  f.box = corners_box(ss, f.v.size(), [&](std::size_t k) -> const P3& { return f.v[k]; });
  f.zlo = HUGE_VAL;
  f.zhi = -HUGE_VAL;
  for (const auto& p : f.v) {
    const Interval z = ss.z_of(p);
    f.zlo = std::min(f.zlo, z.inf());
    f.zhi = std::max(f.zhi, z.sup());
  }
}

// Whether every facet is in one solid (as labelled by solid_labels).
bool all_in_one_solid(const std::vector<int>& solid) {
  return !solid.empty() && solid[0] >= 0 && std::all_of(solid.begin(), solid.end(), [&](int s) { return s == solid[0]; });
}

// Parallel to the screen: every vertex at one depth, known exactly from its
// interval. Common in views along an axis.
template <class Corner>
bool parallel_to_screen(const ScreenScene& ss, std::size_t n, Corner&& corner) {
  const Interval z0 = ss.z_of(corner(0));
  if (!z0.is_point()) return false;
  for (std::size_t k = 1; k < n; ++k) {
    const Interval z = ss.z_of(corner(k));
    if (z.inf() != z0.inf() || z.sup() != z0.sup()) return false;
  }
  return true;
}
bool parallel_to_screen(const ScreenScene& ss, const Facet& f) {
  return parallel_to_screen(ss, f.v.size(), [&](std::size_t k) -> const P3& { return f.v[k]; });
}

// Facet fi's depth plane (f is not edge-on; `parallel`: parallel_to_screen(f);
// its spanning corners are in `exact` unless it is). Parallel to the screen: depth = c.
// Else depth = a x + b y + c from three vertices that are not collinear on
// screen: intervals from the vertices' (exact values from the world, on
// demand), or, where no three vertices' intervals can tell, computed once in GMP.
DepthPlane depth_plane_of(const Facet& f, const ExactSource& exact, std::uint32_t fi, bool parallel) {
  if (parallel) return DepthPlane::of_doubles(0, 0, approx_of(f.v[0].z).inf());
  const std::size_t nv = f.v.size();
  std::array<Interval, 3> abc;
  for (std::size_t k = 1; k + 1 < nv; ++k)
    if (depth_plane(f.v[0], f.v[k], f.v[k + 1], abc)) return DepthPlane::of_source(abc[0], abc[1], abc[2], exact, fi);
  const Num x0 = num(f.v[0].x), y0 = num(f.v[0].y), z0 = num(f.v[0].z);
  for (std::size_t k = 1; k + 1 < nv; ++k) {
    const P3 &p1 = f.v[k], &p2 = f.v[k + 1];
    const Num x1 = num(p1.x) - x0, y1 = num(p1.y) - y0, z1 = num(p1.z) - z0;
    const Num x2 = num(p2.x) - x0, y2 = num(p2.y) - y0, z2 = num(p2.z) - z0;
    const Num nz = x1 * y2 - y1 * x2;
    if (nz == 0) continue;
    const Num a = (z1 * y2 - y1 * z2) / nz, b = (x1 * z2 - z1 * x2) / nz;
    return DepthPlane::of_rationals(to_mpq(a), to_mpq(b), to_mpq(Num(z0 - a * x0 - b * y0)), exact, fi);
  }
  return DepthPlane{};   // (no three corners span it on screen: the zero plane, as a default-made one)
}

// Facet fi's depth plane made, kept in `store` (room reserved beforehand: it
// never moves), and pointed at.
void make_depth_plane(Facet& f, const ExactSource& exact, std::uint32_t fi, bool parallel,
                      std::vector<DepthPlane>& store) {
  store.push_back(depth_plane_of(f, exact, fi, parallel));
  f.plane = &store.back();
}

// Where most pieces are drawn (a small crease angle on a dense mesh), nearly
// every latent one meets a drawn one and is needed after all: they are made
// now, as for a whole map, instead of being looked at, made and bucketed late
// (bunny00 close-up at 2 degrees: 65% drawn, the lines-only map 10% slower than
// the whole map; at 5 degrees, 29% drawn, as fast; at 10, 9% drawn, 1.5x faster).
// Returns how many pieces are to be made now.
std::size_t make_latent_now_where_most_are_drawn(std::vector<CurveMaker::Verdict>& verdict) {
  using V = CurveMaker::Verdict;
  const auto drawn = std::count(verdict.begin(), verdict.end(), V::Drawn);
  const auto latent = std::count(verdict.begin(), verdict.end(), V::Latent);
  if (drawn < latent) return static_cast<std::size_t>(drawn);
  for (V& v : verdict)
    if (v == V::Latent) v = V::Drawn;   // (made as make() makes any piece: drawn or not, by its kind)
  return static_cast<std::size_t>(drawn + latent);
}

// Whether a lines-only drawing draws most edges anyway: on a sample of the edges
// between two faces, those that are creases at its angle (is_crease, on the
// facets' spanning corners) against those that are smooth (all of them drawn
// where smooth ones are). Such a drawing is made as a whole map, and only its
// segments written: looking near its lines first (judging each piece, making
// planes and curves late, telling which curves its lines need) costs more than
// it skips there (bunny00 close-up at crease 0: as many instructions as the
// whole map, and more time). The drawing is the same either way: only the time
// depends on this. (The rule that makes latent pieces now, above, decides on
// the judged pieces themselves, too late to skip the rest.)
bool draws_most_edges(const Scene& scene, const WorldFacets& wf, const std::vector<WorldPiece>& pieces,
                      double cos_crease, bool smooth) {
  if (smooth) return true;
  auto spanning = [&](int f) {
    const std::array<std::uint32_t, 3> id = spanning_ids(scene, wf.facets[static_cast<std::size_t>(f)]);
    return Spanning{scene.vertices[id[0]], scene.vertices[id[1]], scene.vertices[id[2]]};
  };
  std::size_t creases = 0, smooth_edges = 0;
  const std::size_t step = std::max<std::size_t>(1, pieces.size() / 16384);
  for (std::size_t i = 0; i < pieces.size(); i += step) {
    const auto& s = pieces[i].sharers;
    if (s.size() != 2 || wf.facets[static_cast<std::size_t>(s[0].facet)].face == wf.facets[static_cast<std::size_t>(s[1].facet)].face)
      continue;   // (a border, or a polygon's own diagonal: never smooth, never a crease)
    ++(is_crease(spanning(s[0].facet), spanning(s[1].facet), cos_crease) ? creases : smooth_edges);
  }
  return creases > 0 && creases >= smooth_edges;
}
}  // namespace

ScreenScene make_screen_scene(const Scene& scene, const View& view, const Options& opt,
                              Stats& stats, bool latent, bool cull, const WorldScene* world) {
  if (scene.vertices.size() > static_cast<std::size_t>(std::numeric_limits<VertexId>::max()))
    throw std::invalid_argument("the scene has 2^31 vertices or more (vertex ids are 32-bit)");
  auto maker = std::make_shared<CurveMaker>();
  CurveMaker& M = *maker;
  M.scene = &scene;
  M.view = &view;
  M.cos_crease = std::cos(opt.crease_deg * M_PI / 180);
  M.smooth = opt.smooth;
  M.drop_inside_edge_on = cull;
  // Depth is f . p (f the third row): it falls along r x u where f . (r x u) < 0
  // (about -1 for the camera's unit rows), exact. (0: two facets decide, as in
  // perspective.)
  if (!view.perspective)
    M.toward_eye = -world::det<CGAL::Mpzf>(Vec3{0, 0, 0}, M.row(0), M.row(1), M.row(2)).sign();
  const int threads = thread_count(opt.threads, scene.faces.size());
  // The world facets in screen order and their edge pieces: from the world
  // scene where one is kept for many views, else made for this view alone.
  ClosedComponents closed;
  std::vector<int> height_field;   // (camera-free: engine/height_fields.h)
  if (world) {
    filter_counts.calls += world->counted.calls;   // (counted as if made for this view)
    filter_counts.exact += world->counted.exact;
    InViewOrder v = in_view_order(*world, screen_order(world->wf, scene, view, latent, threads), threads);
    M.wf = std::move(v.wf);
    M.pieces = std::move(v.pieces);
    closed = std::move(v.closed);
    height_field = std::move(v.height_field);
  } else {
    M.wf = make_world_facets(scene, threads);
    order_on_screen(M.wf, screen_order(M.wf, scene, view, latent, threads), threads);
  }
  // Each vertex is transformed once. Its image is stored at its place in
  // `used`, not at its input index, so that facets and curves read their
  // vertices nearly in sequence.
  number_by_first_use(M.wf, scene.vertices.size(), M.used, M.local);
  // (Matched here where no world scene brought the pieces; the closed
  // components and height fields only where facets are culled.)
  if (!world && cull) {
    MatchedSolids m = match_edges_and_solids(scene, M.wf, M.local, M.used.size(), /*ranked=*/false, threads);
    M.pieces = std::move(m.edges.pieces);
    closed = std::move(m.closed);
    height_field = std::move(m.height_field);
  }
  if (!world && !cull) M.pieces = match_edges(scene, M.wf, /*cell_bits=*/20, threads);
  WorldFacets& wf = M.wf;
  std::vector<WorldPiece>& pieces = M.pieces;
  if (latent && draws_most_edges(scene, wf, pieces, M.cos_crease, M.smooth)) {
    latent = false;
    stats.count("lines_only_as_whole_map", 1);
  }
  stats.count("faces_degenerate_dropped", wf.degenerate);
  stats.count("faces_nonplanar_fanned", wf.nonplanar);
  stats.count("faces_nonconvex_triangulated", wf.nonconvex);
  stats.count("facets", static_cast<std::int64_t>(wf.facets.size()));

  std::vector<std::uint32_t>& used = M.used;
  ScreenScene ss;
  ss.world = &scene.vertices;
  const int k = M.k = ss.scale_exp = screen_scale(scene, used, view);
  // Exact values, where a predicate needs one, are computed from the world
  // (lazy_leaves.h): a vertex's coordinates from its input doubles, a facet's
  // depth plane from the input vertices that span it.
  auto exact = std::make_shared<ExactSource>();
  exact->vertices = &scene.vertices;
  exact->m = view.m;
  exact->perspective = view.perspective;
  exact->k = k;
  exact->reserve_facets(wf.facets.size());
  ss.exact = exact;
  M.exact = exact.get();
  // Which vertices are in front of the near plane (perspective: Z > 0 and W > 0,
  // decided exactly on binary floats; an orthographic view has no near plane).
  const int nu = static_cast<int>(used.size());
  std::vector<char>& front = M.front;
  front.assign(used.size(), 1);
  std::vector<std::int8_t> zsign(used.size(), 1);   // sign of Z (perspective): the near plane is Z = 0
  if (view.perspective)
    parallel_chunks(nu, 4096, threads, [&](int, Chunk r) {
      for (int u = r.begin; u < r.end; ++u) {
        const Vec3& p = scene.vertices[used[static_cast<std::size_t>(u)]];
        zsign[u] = static_cast<std::int8_t>(projected_sign(view.m[2], p));
        front[u] = zsign[u] > 0 && projected_sign(view.m[3], p) > 0;
      }
    });
  // The images: input vertices as exact values that no rational arithmetic is
  // done for unless a predicate needs them (engine/lazy_leaves.h), made in
  // parallel. A lines-only drawing that the near plane cuts nowhere leaves them
  // for later (only their intervals now): it needs those near its drawn lines
  // (make_images), mostly a few per cent.
  M.all_front = std::all_of(front.begin(), front.end(), [](char f) { return f != 0; });
  const bool later = latent && M.all_front && can_defer_images;
  // A lines-only drawing that will look only near its lines (drawing_cells: every
  // facet in one solid, nothing cut at the near plane) keeps each facet's brief
  // alone; make_facets makes the Facets of those near its lines (the 10^6-
  // triangle terrain: 7 % of them; 104 bytes fewer for each of the others).
  if (cull) ss.solid = solid_labels(closed, height_field, wf.facets.size());   // (camera-free: known now)
  const bool lean = later && cull && all_in_one_solid(ss.solid);
  // Orthographic, it is sparse: even the intervals of the images are made only
  // where asked (make_bounds), a facet's box only where its cells may be looked
  // at (make_boxes; the grid's steps find those from runs of facets' boxes made
  // from the world: world_run_boxes), its facing from the world. (The terrain
  // seen obliquely: 1.5 M coordinates and 10^6 boxes were 0.37 s of its 1.5 s.)
  const bool sparse = lean && !view.perspective && !used.empty();
  ss.images = ImageTable(used.size());
  if (sparse) {
    ss.image_bounds.resize(used.size());
    ss.bounds_made.assign(used.size(), 0);
    M.bounds = ss.image_bounds.data();
    M.bounds_made = ss.bounds_made.data();
  } else if (later) {
    // (Written in place: plain doubles, no chunk's vector made and moved.)
    ss.image_bounds.resize(used.size());
    parallel_chunks(nu, 4096, threads, [&](int, Chunk r) {
      for (int u = r.begin; u < r.end; ++u) {
        M.fetch_after(static_cast<std::size_t>(u));
        ss.image_bounds[static_cast<std::size_t>(u)] = M.bounds_of(static_cast<std::uint32_t>(u));
      }
    });
    M.bounds = ss.image_bounds.data();
  } else {
    parallel_chunks(nu, 1024, threads, [&](int, Chunk r) {
      for (int u = r.begin; u < r.end; ++u) {
        M.fetch_after(static_cast<std::size_t>(u));
        if (front[static_cast<std::size_t>(u)]) ss.images.make(static_cast<std::size_t>(u), M.make_image(static_cast<std::uint32_t>(u)));
      }
    });
  }
  M.sv = ss.images.data();
  auto in_front = [&](std::uint32_t id) { return M.in_front(id); };
  auto image = [&](std::uint32_t id) -> const P3& { return M.image(id); };
  auto clip_point = [&](std::uint32_t a, std::uint32_t b) { return M.clip_point(a, b); };

  std::vector<std::vector<P3>>& clip_edges = M.clip_edges;  // near-plane cuts
  if (view.perspective) {   // (no plane cuts an orthographic view)
    clip_edges.resize(wf.facets.size());
    M.make_clips(threads);
  }
  // Each facet on its own (in parallel, chunks of them): its screen polygon,
  // facing and depth plane. What a chunk culled is counted in its slot (outside, edge-on).
  const int nf = static_cast<int>(wf.facets.size());
  const int facets_per_chunk = 512;
  std::vector<ChunkCounts> culled(static_cast<std::size_t>(chunk_count(nf, facets_per_chunk)));
  // Facing: the sign of the projected area of a screen polygon of n corners,
  // corner(k) its images (a near-plane cut's point, or a vertex's: a leaf, its
  // intervals first, its exact value where those cannot tell) and id(k) their
  // input vertices (-1 for a cut point).
  auto facing_of = [&](std::size_t n, auto&& corner, auto&& id) {
    const CGAL::Sign s = filtered_sign(
        [&] {
          if (n == 3) {   // (most facets: two products, each corner's intervals looked up once)
            const P3 &a = corner(0), &b = corner(1), &c = corner(2);
            const Interval ax = ss.x_of(a), ay = ss.y_of(a);
            return (ss.x_of(b) - ax) * (ss.y_of(c) - ay) - (ss.x_of(c) - ax) * (ss.y_of(b) - ay);
          }
          Interval area2 = 0;
          for (std::size_t k = 0; k < n; ++k) {
            const P3 &p = corner(k), &q = corner((k + 1) % n);
            area2 += ss.x_of(p) * ss.y_of(q) - ss.x_of(q) * ss.y_of(p);
          }
          return area2;
        },
        [&]() -> mpq_class {
          if (!view.perspective) return world_area_sign(view, scene, n, id);
          // (Corners whose images are left for later: made for the question.)
          std::vector<P3> made;
          if (later)
            for (std::size_t k = 0; k < n; ++k)
              made.push_back(M.make_image(static_cast<std::uint32_t>(&corner(k) - ss.images.data())));
          auto at = [&](std::size_t k) -> const P3& { return later ? made[k] : corner(k); };
          mpq_class area2 = 0;
          for (std::size_t k = 0; k < n; ++k) {
            const P3 &p = at(k), &q = at((k + 1) % n);
            area2 += to_mpq(p.x) * to_mpq(q.y) - to_mpq(q.x) * to_mpq(p.y);
          }
          return area2;
        });
    return s > 0 ? Facing::Front : s < 0 ? Facing::Back : Facing::EdgeOn;
  };
  auto project_facet = [&](std::size_t fi, Facet& f, std::int64_t& outside, std::int64_t& edge_on,
                           std::vector<DepthPlane>& planes) {
    const WorldFacet& w = wf.facets[fi];
    f.face = w.face;
    f.planar = w.planar;
    f.split = w.split;
    const std::size_t n = w.v.size();
    // (A diagonal keeps its role on both sides of a cut.)
    auto mark_diagonal = [&](std::size_t k) {
      if (w.role[k] == EdgeRole::Internal && f.v.size() <= 8)
        f.diagonals |= static_cast<std::uint8_t>(1u << (f.v.size() - 1));
    };
    for (std::size_t k = 0; k < n; ++k) {
      std::uint32_t a = w.v[k], b = w.v[(k + 1) % n];
      if (in_front(a)) { f.v.refer(image(a)); f.id.push_back(static_cast<VertexId>(a)); mark_diagonal(k); }
      if (in_front(a) != in_front(b)) {
        f.v.keep(in_front(a) ? clip_point(a, b) : clip_point(b, a));
        f.id.push_back(-1);
        if (!in_front(a)) mark_diagonal(k);   // (from the cut, the edge goes on to b)
        // The cut runs from where the polygon leaves the front half-space to where it re-enters.
        if (in_front(a)) clip_edges[fi].push_back(f.v.back());
        else clip_edges[fi].insert(clip_edges[fi].begin(), f.v.back());
      }
    }
    if (f.v.size() < 3) { f.v.clear(); f.id.clear(); f.diagonals = 0; ++outside; return; }
    f.projected = true;
    f.facing = facing_of(
        f.v.size(), [&](std::size_t k) -> const P3& { return f.v[k]; }, [&](std::size_t k) { return f.id[k]; });
    if (f.facing == Facing::EdgeOn) { ++edge_on; return; }
    bound(ss, f);
    f.occluder = true;
    // Its plane's spanning corners (the crease test reads them too), and its
    // depth plane, unless a lines-only drawing makes it later for the facets
    // its cells list (make_depth_planes).
    const bool parallel = parallel_to_screen(ss, f);
    if (!parallel) exact->spanning[fi] = spanning_ids(scene, w);
    if (!latent) make_depth_plane(f, *exact, static_cast<std::uint32_t>(fi), parallel, planes);
  };
  // What project_facet gives a facet's brief, for a lean scene's (every corner
  // in front of the near plane: its polygon is its world facet's), read from
  // its corners' kept intervals with no Facet made.
  auto brief_facet = [&](std::size_t fi, FacetBrief& b, std::int64_t& edge_on) {
    const WorldFacet& w = wf.facets[fi];
    const std::size_t n = w.v.size();
    auto corner = [&](std::size_t k) -> const P3& { return image(w.v[k]); };
    b.face = w.face;
    b.projected = true;
    b.facing = facing_of(n, corner, [&](std::size_t k) { return w.v[k]; });
    if (b.facing == Facing::EdgeOn) { ++edge_on; return; }
    b.box = corners_box(ss, n, corner);
    b.occluder = true;
    if (!parallel_to_screen(ss, n, corner)) exact->spanning[fi] = spanning_ids(scene, w);
  };
  // A sparse scene's brief: its facing from its world corners (the sign of the
  // polygon's area vector, a fan of cross products, along r x u: as
  // world_area_sign, on intervals first), no box yet (make_boxes), its plane's
  // spanning corners (its Facet, if made, may be parallel to the screen: they
  // are then not read).
  std::array<Interval, 3> axis;   // r x u, the view's direction (intervals)
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const auto &r = view.m[0], &u = view.m[1];
    auto at = [](double d) { return Interval(d); };
    axis = {at(r[1]) * at(u[2]) - at(r[2]) * at(u[1]), at(r[2]) * at(u[0]) - at(r[0]) * at(u[2]),
            at(r[0]) * at(u[1]) - at(r[1]) * at(u[0])};
  }
  auto sparse_brief = [&](std::size_t fi, FacetBrief& b, std::int64_t& edge_on) {
    const WorldFacet& w = wf.facets[fi];
    const std::size_t n = w.v.size();
    b.face = w.face;
    b.projected = true;
    auto vertex = [&](std::size_t k) -> const Vec3& { return scene.vertices[w.v[k]]; };
    const CGAL::Sign s = filtered_sign(
        [&] {
          const Vec3& o = vertex(0);
          Interval ax = 0, ay = 0, az = 0;
          for (std::size_t k = 1; k + 1 < n; ++k) {
            const Vec3 &p = vertex(k), &q = vertex(k + 1);
            const Interval px = Interval(p.x) - o.x, py = Interval(p.y) - o.y, pz = Interval(p.z) - o.z;
            const Interval qx = Interval(q.x) - o.x, qy = Interval(q.y) - o.y, qz = Interval(q.z) - o.z;
            ax += py * qz - pz * qy;
            ay += pz * qx - px * qz;
            az += px * qy - py * qx;
          }
          return axis[0] * ax + axis[1] * ay + axis[2] * az;
        },
        [&]() -> mpq_class { return world_area_sign(view, scene, n, [&](std::size_t k) { return w.v[k]; }); });
    b.facing = s > 0 ? Facing::Front : s < 0 ? Facing::Back : Facing::EdgeOn;
    if (b.facing == Facing::EdgeOn) { ++edge_on; return; }
    b.occluder = true;
    exact->spanning[fi] = spanning_ids(scene, w);
  };
  // (A chunk's planes in a vector of their own, its room made as it starts.)
  ss.planes.resize(culled.size());
  // (Made in their places: a Facet holds no kernel number, so default-made on
  // one thread it is nothing the threads share.)
  if (lean) ss.briefs.resize(static_cast<std::size_t>(nf));
  else ss.facets.resize(static_cast<std::size_t>(nf));
  parallel_chunks(nf, facets_per_chunk, threads, [&](int c, Chunk r) {
    auto& [outside, edge_on] = culled[static_cast<std::size_t>(c)];
    std::vector<DepthPlane>& planes = ss.planes[static_cast<std::size_t>(c)];
    if (!latent) planes.reserve(static_cast<std::size_t>(facets_per_chunk));
#ifndef VISMAP_FLOAT_KERNEL
    // (The facing tests' intervals need upward rounding: set once per chunk,
    // not twice per facet, ~25 ms of a 10^6-facet view. Nothing else here
    // computes on doubles that round to nearest; the exact fallbacks run
    // under filtered_sign's NearestRounding.)
    UpwardRounding upward;
#endif
    for (auto fi = static_cast<std::size_t>(r.begin); fi < static_cast<std::size_t>(r.end); ++fi) {
      if (!lean) {
        project_facet(fi, ss.facets[fi], outside, edge_on, planes);
        continue;
      }
      if (sparse) sparse_brief(fi, ss.briefs[fi], edge_on);
      else brief_facet(fi, ss.briefs[fi], edge_on);
    }
  });
  const auto [outside, edge_on] = summed(culled);
  stats.count("culled_outside_view", outside);
  stats.count("culled_edge_on", edge_on);

  if (cull) {
    cull_by_closed_solids(ss, M, view, zsign, closed, threads, stats);
    stats.count("height_field_facets", std::count_if(height_field.begin(), height_field.end(), [](int l) { return l >= 0; }));
  }

  M.look.resize(ss.facet_count());
  parallel_chunks(static_cast<int>(ss.facet_count()), 16384, threads, [&](int, Chunk r) {
    for (auto fi = static_cast<std::size_t>(r.begin); fi < static_cast<std::size_t>(r.end); ++fi)
      M.look[fi] = CurveMaker::look_of(ss.brief(fi), wf.facets[fi]);
  });

  // Chunks of pieces in parallel, appended in piece order a wave of chunks at a
  // time (parallel_append): the curves are never held twice (curves made in
  // place instead would be default-made first, and their placeholder numbers,
  // one shared object, then released by every thread at once). Latent curves:
  // only their boxes are kept. (One Curve per chunk is made into again and
  // again: make() sets every field.)
  const int np = static_cast<int>(pieces.size()), size = 1024, chunks = chunk_count(np, size);
  // A lines-only drawing judges every piece first (most are left latent), then
  // makes the images of the drawn ones' ends, where images are left for later.
  using V = CurveMaker::Verdict;
  std::vector<V> verdict;
  std::size_t made_here = pieces.size();   // (at most: room is reserved for them below)
  if (latent) {
    verdict.resize(pieces.size());
    parallel_chunks(np, 4096, threads, [&](int, Chunk r) {
      for (int i = r.begin; i < r.end; ++i) verdict[static_cast<std::size_t>(i)] = M.judge(pieces[static_cast<std::size_t>(i)]);
    });
    made_here = make_latent_now_where_most_are_drawn(verdict);
    if (later) {
      std::vector<std::uint32_t> ends;
      for (std::size_t i = 0; i < pieces.size(); ++i)
        if (verdict[i] == V::Drawn) {
          ends.push_back(M.local[pieces[i].a]);
          ends.push_back(M.local[pieces[i].b]);
        }
      make_images_of(M, ss.images, ends, threads);
      make_bounds_of(M, ss, ends, threads);
    }
  }
  // Room for every curve made here, so that none is moved (a vector grown by
  // doubling held up to twice its curves at once, in fresh pages): where pieces
  // are judged, those drawn; + near-plane cuts; + intersection lines later.
  // (Reserved, not touched: room never used costs no memory.)
  ss.curves.reserve(made_here + ss.facet_count() / 8);
  std::vector<CurveMaker::Dropped> dropped(static_cast<std::size_t>(chunks));
  std::vector<std::vector<int>> left(static_cast<std::size_t>(chunks));
  const std::size_t first_ends = ss.ends.size();
  for (int k = 0; k < chunks; ++k) ss.ends.emplace_back();
  parallel_append(ss.curves, chunks, threads, [&](int k, std::vector<Curve>& out) {
    const Chunk r = chunk(k, np, size);
    std::deque<P3>& ends = ss.ends[first_ends + static_cast<std::size_t>(k)];
    std::vector<int> latent_here;   // (filled here, stored once)
    CurveMaker::Dropped count{};
    if (!latent) out.reserve(static_cast<std::size_t>(r.end - r.begin));
    Curve c;
    for (int i = r.begin; i < r.end; ++i) {
      const WorldPiece& wp = pieces[static_cast<std::size_t>(i)];
      if (latent) {   // (judged first: most pieces of a lines-only drawing are never made)
        const V v = verdict[static_cast<std::size_t>(i)];
        if (v == V::Latent) { latent_here.push_back(i); continue; }
        if (v != V::Drawn) { ++count[static_cast<std::size_t>(v)]; continue; }   // (as make() counts)
      }
      if (M.make(wp, c, count, ends)) out.push_back(std::move(c));
    }
    left[static_cast<std::size_t>(k)] = std::move(latent_here);
    dropped[static_cast<std::size_t>(k)] = count;
  });
  // (The normals' estimates have served: a curve made late tests its crease on
  // its corners. 16 bytes a facet fewer from here on.)
  std::vector<world::UnitNormal>().swap(wf.normals);
  std::size_t nlatent = 0;
  for (const auto& l : left) nlatent += l.size();
  ss.latent_piece.reserve(nlatent);
  for (auto& l : left) {
    ss.latent_piece.insert(ss.latent_piece.end(), l.begin(), l.end());
    std::vector<int>().swap(l);
  }
  std::int64_t dropped_hidden = 0, dropped_clipped = 0, dropped_point = 0, dropped_in_plane = 0;
  for (const auto& d : dropped) {
    dropped_hidden += d[0];
    dropped_clipped += d[1];
    dropped_point += d[2];
    dropped_in_plane += d[3];
  }
  // The near-plane cut of a facet bounds its region but is never drawn.
  std::deque<P3>& cut_ends = ss.ends.emplace_back();
  for (std::size_t fi = 0; fi < clip_edges.size(); ++fi) {
    const auto& ce = clip_edges[fi];
    if (ce.size() != 2 || !ss.brief(fi).occluder || equal_points(ce[0].xy(), ce[1].xy())) continue;
    Curve c;
    c.s = &cut_ends.emplace_back(ce[0]);
    c.t = &cut_ends.emplace_back(ce[1]);
    c.sharers = {static_cast<int>(fi)};
    // The polygon's edge from where it leaves the front half-space (ce[1]) to
    // where it re-enters (ce[0]): the cut points are shared, known by identity.
    const auto& fv = ss.facet(fi).v;
    int edge = -1;
    for (std::size_t k = 0; k < fv.size() && edge < 0; ++k)
      if (same_rep(fv[k].xy(), ce[1].xy()) && same_rep(fv[(k + 1) % fv.size()].xy(), ce[0].xy()))
        edge = static_cast<int>(k);
    c.sharer_edge = {edge};
    c.order_face = ss.brief(fi).face;
    c.box = box_of(*c.s) + box_of(*c.t);
    ss.curves.push_back(std::move(c));
  }
  stats.count("edge_pieces", static_cast<std::int64_t>(pieces.size()));
  stats.count("edges_culled_back", dropped_hidden);
  stats.count("edges_culled_outside_view", dropped_clipped);
  stats.count("edges_seen_end_on", dropped_point);
  stats.count("edges_inside_edge_on_planes", dropped_in_plane);
  ss.planes_later = latent;
  if (latent) {
    stats.count("curves_latent", static_cast<std::int64_t>(ss.latent_piece.size()));
    // (Kept while it has latent curves or images to make; else freed now, as for a whole map.)
    if (!ss.latent_piece.empty() || later) ss.maker = std::move(maker);
  }
  if (!cull) ss.maker = std::move(maker);   // (the hidden lines' pass reads the world facets)
  return ss;
}

void make_images(ScreenScene& ss, const std::vector<std::uint32_t>& places, int threads) {
  if (ss.image_bounds.empty() || places.empty()) return;   // (every image made)
  make_images_of(*ss.maker, ss.images, places, threads);
  make_bounds_of(*ss.maker, ss, places, threads);   // (read again and again where they are made)
}

void make_corner_images(ScreenScene& ss, const std::vector<char>& which, int threads) {
  if (ss.image_bounds.empty()) return;
  std::vector<std::uint32_t> places;
  if (which.empty()) {   // (every facet: every image, a vertex being some facet's corner)
    places.resize(ss.images.size());
    for (std::size_t u = 0; u < places.size(); ++u) places[u] = static_cast<std::uint32_t>(u);
  } else {
    for (std::size_t fi = 0; fi < ss.facet_count(); ++fi)
      if (which[fi])
        for (const P3& p : ss.facet(fi).v) places.push_back(static_cast<std::uint32_t>(&p - ss.images.data()));
  }
  make_images(ss, places, threads);
}

ImageBounds ScreenScene::bounds_now(std::size_t u) const { return maker->bounds_of(static_cast<std::uint32_t>(u)); }

void make_bounds(ScreenScene& ss, const std::vector<std::uint32_t>& places, int threads) {
  if (ss.sparse()) make_bounds_of(*ss.maker, ss, places, threads);
}

namespace {
void make_bounds_of(const CurveMaker& M, ScreenScene& ss, const std::vector<std::uint32_t>& places, int threads) {
  if (!ss.sparse()) return;
  std::vector<std::uint32_t> to_make;   // (each once: marked 2 while listed)
  for (const std::uint32_t u : places)
    if (ss.bounds_made[u] == 0) {
      ss.bounds_made[u] = 2;
      to_make.push_back(u);
    }
  parallel_chunks(static_cast<int>(to_make.size()), 4096, threads, [&](int, Chunk r) {
    for (int i = r.begin; i < r.end; ++i) {
      const std::uint32_t u = to_make[static_cast<std::size_t>(i)];
      ss.image_bounds[u] = M.bounds_of(u);
      ss.bounds_made[u] = 1;
    }
  });
}
}  // namespace

void make_boxes(ScreenScene& ss, const std::vector<char>& which, int threads) {
  if (!ss.sparse()) return;
  const CurveMaker& M = *ss.maker;
  // Those without one: projected and not edge-on (whose box stays empty, as a
  // lean scene's brief leaves it), not made yet.
  std::vector<std::uint32_t> facets, places;
  for (std::size_t fi = 0; fi < which.size(); ++fi) {
    const FacetBrief& b = ss.briefs[fi];
    if (!which[fi] || !b.projected || b.facing == Facing::EdgeOn || b.box.xmin() <= b.box.xmax()) continue;
    facets.push_back(static_cast<std::uint32_t>(fi));
    for (const std::uint32_t id : M.wf.facets[fi].v) places.push_back(M.local[id]);
  }
  make_bounds(ss, places, threads);
  parallel_chunks(static_cast<int>(facets.size()), 4096, threads, [&](int, Chunk r) {
    for (int i = r.begin; i < r.end; ++i) {
      const std::size_t fi = facets[static_cast<std::size_t>(i)];
      const auto& v = M.wf.facets[fi].v;
      ss.briefs[fi].box = corners_box(ss, v.size(), [&](std::size_t k) -> const P3& { return ss.images.data()[M.local[v[k]]]; });
    }
  });
}

std::vector<CGAL::Bbox_2> world_run_boxes(ScreenScene& ss, int run, int threads) {
  if (!ss.sparse()) return {};
  const CurveMaker& M = *ss.maker;
  const std::vector<Vec3>& vertices = M.scene->vertices;
  const int nf = static_cast<int>(M.wf.facets.size()), runs = (nf + run - 1) / run;
  std::vector<CGAL::Bbox_2> box(static_cast<std::size_t>(runs));   // (each empty)
  std::vector<char> unbounded(static_cast<std::size_t>(runs), 0);
  // The screen scale 2^k as an interval factor (where it is a double; else no
  // bound: every run reaches everything).
  const bool scalable = M.k >= -1022 && M.k <= 1023;
  const double scale = scalable ? std::ldexp(1.0, M.k) : 0;
  parallel_chunks(runs, 64, threads, [&](int, Chunk r) {
    CGAL::Protect_FPU_rounding<true> upward;
    for (int k = r.begin; k < r.end; ++k) {
      // The world box of the run's corners (exact: minima and maxima of doubles).
      double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
      for (int fi = k * run; fi < std::min(nf, (k + 1) * run); ++fi)
        for (const std::uint32_t id : M.wf.facets[static_cast<std::size_t>(fi)].v) {
          const Vec3& p = vertices[id];
          const double c[3] = {p.x, p.y, p.z};
          for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], c[a]);
            hi[a] = std::max(hi[a], c[a]);
          }
        }
      if (lo[0] > hi[0]) continue;   // (no corner: an empty box)
      // Screen x and y over it, on intervals (an affine map: they hold its image).
      Interval xy[2];
      for (int row = 0; row < 2; ++row) {
        const auto& m = M.view->m[static_cast<std::size_t>(row)];
        Interval v = Interval(m[3]);
        for (int a = 0; a < 3; ++a) v += Interval(m[static_cast<std::size_t>(a)]) * Interval(lo[a], hi[a]);
        xy[row] = v * Interval(scale);
      }
      const bool bounded = scalable && std::isfinite(xy[0].inf()) && std::isfinite(xy[0].sup()) &&
                           std::isfinite(xy[1].inf()) && std::isfinite(xy[1].sup());
      if (bounded) box[static_cast<std::size_t>(k)] = CGAL::Bbox_2(xy[0].inf(), xy[1].inf(), xy[0].sup(), xy[1].sup());
      else unbounded[static_cast<std::size_t>(k)] = 1;
    }
  });
  // (Where the intervals overflow: the run's facets' own boxes.)
  if (std::find(unbounded.begin(), unbounded.end(), 1) == unbounded.end()) return box;
  std::vector<char> which(static_cast<std::size_t>(nf), 0);
  for (int fi = 0; fi < nf; ++fi) which[static_cast<std::size_t>(fi)] = unbounded[static_cast<std::size_t>(fi / run)];
  make_boxes(ss, which, threads);
  for (int fi = 0; fi < nf; ++fi)
    if (which[static_cast<std::size_t>(fi)]) box[static_cast<std::size_t>(fi / run)] += ss.briefs[static_cast<std::size_t>(fi)].box;
  return box;
}

const WorldFacets* world_facets_of(const ScreenScene& ss) { return ss.maker ? &ss.maker->wf : nullptr; }
void make_depth_planes(ScreenScene& ss, const std::vector<char>& which, int threads) {
  const int nf = static_cast<int>(ss.facet_count()), size = 4096;
  std::vector<std::vector<DepthPlane>> made(static_cast<std::size_t>(chunk_count(nf, size)));
  parallel_chunks(nf, size, threads, [&](int k, Chunk r) {
    std::vector<DepthPlane>& planes = made[static_cast<std::size_t>(k)];
    planes.reserve(static_cast<std::size_t>(std::count(which.begin() + r.begin, which.begin() + r.end, 1)));
    for (int fi = r.begin; fi < r.end; ++fi)
      if (which[static_cast<std::size_t>(fi)]) {
        Facet& f = ss.facet(static_cast<std::size_t>(fi));
        make_depth_plane(f, *ss.exact, static_cast<std::uint32_t>(fi), parallel_to_screen(ss, f), planes);
      }
  });
  // (Moved vectors keep their items where they are: the facets' pointers hold.)
  for (std::vector<DepthPlane>& planes : made) ss.planes.push_back(std::move(planes));
}

const std::vector<WorldPiece>* latent_pieces_of(const ScreenScene& ss) { return ss.maker ? &ss.maker->pieces : nullptr; }
CGAL::Bbox_2 latent_box(const ScreenScene& ss, std::size_t i) {
  return ss.maker->latent_box(ss.maker->pieces[static_cast<std::size_t>(ss.latent_piece[i])]);
}
std::array<const P3*, 2> latent_ends(const ScreenScene& ss, std::size_t i) {
  const CurveMaker& M = *ss.maker;
  const WorldPiece& wp = M.pieces[static_cast<std::size_t>(ss.latent_piece[i])];
  return {M.in_front(wp.a) ? &M.image(wp.a) : nullptr, M.in_front(wp.b) ? &M.image(wp.b) : nullptr};
}

void ScreenScene::not_made() {
  throw std::logic_error("screen scene: a facet read before it was made (engine bug)");
}

void make_facets(ScreenScene& ss, const std::vector<char>& which, int threads) {
  if (!ss.lean()) return;
  const CurveMaker& M = *ss.maker;
  const std::size_t n = ss.briefs.size();
  if (ss.made_at.empty()) ss.made_at.assign(n, ScreenScene::kNotMade);
  std::vector<std::uint32_t> to_make;
  for (std::size_t fi = 0; fi < n; ++fi)
    if ((which.empty() || which[fi]) && ss.made_at[fi] == ScreenScene::kNotMade) {
      ss.made_at[fi] = static_cast<std::uint32_t>(ss.facets.size() + to_make.size());
      to_make.push_back(static_cast<std::uint32_t>(fi));
    }
  const std::size_t first = ss.facets.size();
  ss.facets.resize(first + to_make.size());
  // As project_facet makes them (nothing is cut: every corner is its vertex's image).
  parallel_chunks(static_cast<int>(to_make.size()), 4096, threads, [&](int, Chunk r) {
    for (int i = r.begin; i < r.end; ++i) {
      const std::size_t fi = to_make[static_cast<std::size_t>(i)];
      Facet& f = ss.facets[first + static_cast<std::size_t>(i)];
      static_cast<FacetBrief&>(f) = ss.briefs[fi];
      const WorldFacet& w = M.wf.facets[fi];
      f.planar = w.planar;
      f.split = w.split;
      if (!f.projected) continue;
      for (std::size_t k = 0; k < w.v.size(); ++k) {
        f.v.refer(ss.images.data()[M.local[w.v[k]]]);
        f.id.push_back(static_cast<VertexId>(w.v[k]));
        if (w.role[k] == EdgeRole::Internal && f.v.size() <= 8) f.diagonals |= static_cast<std::uint8_t>(1u << (f.v.size() - 1));
      }
      if (f.facing != Facing::EdgeOn) bound(ss, f);   // (its box again: the brief's)
    }
  });
}

SmallVec<const P3*, 4> corners_of(const ScreenScene& ss, std::size_t fi) {
  SmallVec<const P3*, 4> c;
  if (const Facet* f = ss.made_facet(fi)) {
    for (const P3& p : f->v) c.push_back(&p);
    return c;
  }
  if (!ss.brief(fi).projected) return c;
  const CurveMaker& M = *ss.maker;
  for (const std::uint32_t id : M.wf.facets[fi].v) c.push_back(&ss.images.data()[M.local[id]]);
  return c;
}

void make_latent_curves(ScreenScene& ss, const std::vector<char>& wanted, int threads) {
  std::vector<int> pick;
  for (std::size_t i = 0; i < wanted.size(); ++i)
    if (wanted[i]) pick.push_back(ss.latent_piece[i]);
  std::vector<std::uint32_t> ends;   // (their images, where left for later)
  if (!ss.image_bounds.empty())
    for (int i : pick)
      for (std::uint32_t id : {ss.maker->pieces[static_cast<std::size_t>(i)].a, ss.maker->pieces[static_cast<std::size_t>(i)].b})
        ends.push_back(ss.maker->local[id]);
  make_images(ss, ends, threads);
  const int n = static_cast<int>(pick.size()), size = 1024, chunks = chunk_count(n, size);
  const std::size_t first_ends = ss.ends.size();
  for (int k = 0; k < chunks; ++k) ss.ends.emplace_back();
  ss.curves.reserve(ss.curves.size() + pick.size());   // (moved at most once, not grown by doubling)
  parallel_append(ss.curves, chunks, threads, [&](int k, std::vector<Curve>& out) {
    CurveMaker::Dropped dropped{};   // (counted when it was left latent)
    std::deque<P3>& ends = ss.ends[first_ends + static_cast<std::size_t>(k)];
    const Chunk r = chunk(k, n, size);
    for (int i = r.begin; i < r.end; ++i) {
      Curve c;
      if (ss.maker->make(ss.maker->pieces[static_cast<std::size_t>(pick[i])], c, dropped, ends))
        out.push_back(std::move(c));
    }
  });
  std::vector<int>().swap(ss.latent_piece);
  ss.maker.reset();
}

VISMAP_KERNEL_END
}  // namespace vismap::engine
