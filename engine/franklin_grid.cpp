#include "engine/franklin_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <optional>
#include <span>
#include <type_traits>

#include "engine/convex_inside.h"
#include "engine/lazy_leaves.h"
#include "engine/midpoint_probe.h"
#include "engine/overlap_cuts.h"
#include "engine/parallel.h"
#include "engine/world_exact.h"

namespace vismap::engine {
VISMAP_KERNEL_BEGIN
namespace {


// The cell that holds a coordinate under the half-open rule [X_i, X_i+1) (the
// last cell is closed): guessed from its interval iv, confirmed on the interval
// or, where that cannot tell, on its exact value (exact() -> mpq_class).
template <class Exact>
int cell_index_of(const Axis& bounds, const Interval& iv, Exact&& exact) {
  const int last = bounds.cells() - 1;
  auto less = [&](double b) {   // v < b
    if (iv.sup() < b) return true;
    if (iv.inf() >= b) return false;
    return exact() < b;
  };
  int i = bounds.index(CGAL::to_double(iv));
  while (i > 0 && less(bounds[i])) --i;
  while (i < last && !less(bounds[i + 1])) ++i;
  return i;
}

CellRange range_of(const Grid& g, const CGAL::Bbox_2& b) {
  return {g.X.index(b.xmin()), g.X.index(b.xmax()), g.Y.index(b.ymin()), g.Y.index(b.ymax())};
}

// Each screen image's cells (those of its box). A box made of images (a facet's,
// a curve's) reaches the hull of its images' cells, Axis::index being monotone:
// four lookups per image instead of four per box (the terrain's facets and
// latent curves took 10 M lookups, 5 % of a lines-only drawing).
class ImageCells {
 public:
  ImageCells(const Grid& g, const ScreenScene& ss, int threads) : images_(ss.images), range_(ss.images.size()) {
    parallel_chunks(static_cast<int>(range_.size()), 8192, threads, [&](int, Chunk r) {
      for (int i = r.begin; i < r.end; ++i) {
        const P3& p = images_[static_cast<std::size_t>(i)];   // (a slot: perhaps not made)
        if (ss.kept_place(p) < 0 && !images_.made(static_cast<std::size_t>(i))) continue;   // (behind the near plane)
        const Interval x = ss.x_of(p), y = ss.y_of(p);   // (as a box of it takes them)
        range_[static_cast<std::size_t>(i)] = range_of(g, CGAL::Bbox_2(x.inf(), y.inf(), x.sup(), y.sup()));
      }
    });
  }
  // The cells of the box of points p[0 .. n); false where one is not an image.
  template <class Points>
  bool hull(const Points& p, std::size_t n, CellRange& r) const {
    for (std::size_t k = 0; k < n; ++k) {
      const CellRange* c = of(p[k]);
      if (!c) return false;
      r = k == 0 ? *c : CellRange{std::min(r.x0, c->x0), std::max(r.x1, c->x1), std::min(r.y0, c->y0), std::max(r.y1, c->y1)};
    }
    return n > 0;
  }

 private:
  const CellRange* of(const P3* p) const {
    const std::less<const P3*> before;
    if (!p || before(p, images_.data()) || !before(p, images_.data() + images_.size())) return nullptr;
    return &range_[static_cast<std::size_t>(p - images_.data())];
  }
  const CellRange* of(const P3& p) const { return of(&p); }
  const ImageTable& images_;
  std::vector<CellRange> range_;
};

// A cell corner: exact doubles. The corner tests are the most numerous predicates
// of steps 5-6, so they run on the numbers' interval approximations first and
// fall back to exact rationals only when the intervals cannot decide (counted
// with CGAL's own filter failures).
struct Corner {
  double x, y;
};
std::array<Corner, 4> corners(const Grid& g, int ix, int iy) {
  return {Corner{g.X[ix], g.Y[iy]}, Corner{g.X[ix + 1], g.Y[iy]}, Corner{g.X[ix + 1], g.Y[iy + 1]},
          Corner{g.X[ix], g.Y[iy + 1]}};
}

bool same_plane(const Facet& f, const Facet& b) { return *f.plane == *b.plane; }

// sign(depth of f - depth of b) at corner p.
CGAL::Sign depth_order(const Facet& f, const Facet& b, const Corner& p) {
  return filtered_sign(
      [&] {
        return (f.plane->approx(0) - b.plane->approx(0)) * p.x + (f.plane->approx(1) - b.plane->approx(1)) * p.y +
               (f.plane->approx(2) - b.plane->approx(2));
      },
      [&]() -> mpq_class {
        // Mostly facets in one plane (a flat part of a mesh): their exact planes,
        // computed once per facet, are compared instead of evaluated at p.
        if (same_plane(f, b)) return 0;
        const auto F = f.plane->exact(), B = b.plane->exact();
        return (F[0] - B[0]) * p.x + (F[1] - B[1]) * p.y + (F[2] - B[2]);
      });
}

// Orientation of (u, v, p): positive when p is left of u -> v.
CGAL::Sign orientation(const P3& u, const P3& v, const Corner& p) {
  return filtered_sign(
      [&] {
        return (approx_of(v.x) - approx_of(u.x)) * (p.y - approx_of(u.y)) -
               (approx_of(v.y) - approx_of(u.y)) * (p.x - approx_of(u.x));
      },
      [&]() -> mpq_class { return orient_sign(to_mpq(u.x), to_mpq(u.y), to_mpq(v.x), to_mpq(v.y), p.x, p.y); });
}

bool in_cell(const Grid& g, int ix, int iy, const P2& p) {   // (no lazy coordinate built)
  return cell_index_of(g.X, approx_x(p), [&] { return exact_x(p); }) == ix &&
         cell_index_of(g.Y, approx_y(p), [&] { return exact_y(p); }) == iy;
}

}  // namespace

bool strictly_inside(const Facet& f, const P2& p) {
  return strictly_inside_convex(f.v.size(), turn(f), [&](std::size_t i, std::size_t j) {
    return static_cast<int>(CGAL::orientation(f.v[i].xy(), f.v[j].xy(), p));
  });
}

namespace {

// Corner p strictly inside the projection of the convex facet f.
bool strictly_inside(const Facet& f, const Corner& p) {
  return strictly_inside_convex(f.v.size(), turn(f), [&](std::size_t i, std::size_t j) {
    return static_cast<int>(orientation(f.v[i], f.v[j], p));
  });
}

// f is hidden by b everywhere in the closed cell (b covers it): strictly deeper at
// the 4 corners (depths are affine, so everywhere, and in a neighbourhood), or in
// b's very plane with a higher face index.
bool behind_throughout(const Facet& f, const Facet& b, const std::array<Corner, 4>& c) {
  // Depth ranges apart: b's depths over the cell (which it covers) are its
  // vertices' convex combinations, as f's are over its own points.
  if (f.zlo > b.zhi) return true;
  for (const Corner& p : c) {
    const CGAL::Sign s = depth_order(f, b, p);
    if (s == CGAL::POSITIVE) continue;
    // Nearer at a corner: neither deeper nor in b's plane (no exact plane compared).
    if (s == CGAL::NEGATIVE) return false;
    // As deep at a corner: hidden only if in b's very plane, behind it by index.
    return b.face < f.face && same_plane(f, b);
  }
  return true;
}

// Input vertex `id` (a canonical id, not -1).
const Vec3& vertex_at(const std::vector<Vec3>& input, long id) { return input[static_cast<std::size_t>(id)]; }

}  // namespace

CGAL::Sign depth_above(const P3& p, const Facet& f, const std::vector<Vec3>* world, long id) {
  return filtered_sign(
      [&] {
        return approx_of(p.z) -
               (f.plane->approx(0) * approx_of(p.x) + f.plane->approx(1) * approx_of(p.y) + f.plane->approx(2));
      },
      [&]() -> mpq_class {
        if (world && id >= 0 && in_world_plane(*world, id, f)) return 0;
        const auto F = f.plane->exact();
        return to_mpq(p.z) - (F[0] * to_mpq(p.x) + F[1] * to_mpq(p.y) + F[2]);
      });
}

namespace {

// Both points strictly behind the plane of b: the whole segment is. (Used with b
// a cell's blocker.)
bool curve_behind(const Curve& cv, const Facet& b, const std::vector<Vec3>* world) {
  // (Or all its depths beyond b's over the cell, which b covers: hidden there.)
  if (std::min(approx_of(cv.s->z).inf(), approx_of(cv.t->z).inf()) > b.zhi) return true;
  // An end point that is a corner of b lies in its plane: known without arithmetic
  // (the exact zero no filter can settle).
  if (b.has_vertex(cv.vs) || b.has_vertex(cv.vt)) return false;
  return depth_above(*cv.s, b, world, cv.vs) == CGAL::POSITIVE && depth_above(*cv.t, b, world, cv.vt) == CGAL::POSITIVE;
}

// The part of a curve in a closed cell: its two ends, each enclosed in a box
// (Liang-Barsky clipping of the end points' intervals, under the caller's
// upward rounding); false where the intervals show no part (a curve listed in
// a cell its box reaches only by rounding). A box spans the cell where a
// direction's sign is unknown.
struct CellPart {
  std::array<Interval, 2> x, y;   // end k in [x[k].inf, x[k].sup] x [y[k].inf, y[k].sup]
  CGAL::Bbox_2 box() const {
    return {std::min(x[0].inf(), x[1].inf()), std::min(y[0].inf(), y[1].inf()), std::max(x[0].sup(), x[1].sup()),
            std::max(y[0].sup(), y[1].sup())};
  }
};
bool part_in_cell(const Curve& cv, const std::array<Corner, 4>& c, CellPart& part) {
  const Interval sx = approx_of(cv.s->x), sy = approx_of(cv.s->y);
  const Interval dx = approx_of(cv.t->x) - sx, dy = approx_of(cv.t->y) - sy;
  // The part is s + l (t - s) for l in [enter, leave], enter = max(0, the
  // parameters where it enters the slabs), leave = min(1, where it leaves):
  // each bounded below and above.
  double enter_lo = 0, enter_hi = 0, leave_lo = 1, leave_hi = 1;
  auto slab = [&](const Interval& s, const Interval& d, double lo, double hi) {
    if (d.inf() > 0 || d.sup() < 0) {
      const Interval a = (Interval(lo) - s) / d, b = (Interval(hi) - s) / d;
      const Interval& in = d.inf() > 0 ? a : b;
      const Interval& out = d.inf() > 0 ? b : a;
      enter_lo = std::max(enter_lo, in.inf()), enter_hi = std::max(enter_hi, in.sup());
      leave_lo = std::min(leave_lo, out.inf()), leave_hi = std::min(leave_hi, out.sup());
    } else if (!(d.inf() == 0 && d.sup() == 0)) {   // (exactly parallel: the whole curve is in the slab)
      enter_hi = 1;   // (this slab's parameters unknown: enter and leave anywhere in [0, 1])
      leave_lo = 0;
    }
  };
  slab(sx, dx, c[0].x, c[2].x);
  slab(sy, dy, c[0].y, c[2].y);
  bool some = true;
  auto within = [&](double lo, double hi, double from, double to) {   // [lo, hi] clamped to [from, to]
    lo = std::max(lo, from), hi = std::min(hi, to);
    some = some && lo <= hi;
    return some ? Interval(lo, hi) : Interval(from);
  };
  const Interval enter = within(enter_lo, enter_hi, 0, 1), leave = within(leave_lo, leave_hi, 0, 1);
  for (int k = 0; k < 2; ++k) {
    const Interval& l = k == 0 ? enter : leave;
    const Interval x = sx + l * dx, y = sy + l * dy;
    part.x[k] = within(x.inf(), x.sup(), c[0].x, c[2].x);
    part.y[k] = within(y.inf(), y.sup(), c[0].y, c[2].y);
  }
  return some;
}

// The boxes of part's ends strictly inside the convex facet f, told on
// intervals (false where they cannot tell): then so is the part.
bool part_inside(const Facet& f, const CellPart& part) {
  const std::size_t n = f.v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const P3 &u = f.v[i], &v = f.v[(i + 1) % n];
    const Interval ux = approx_of(u.x), uy = approx_of(u.y), ex = approx_of(v.x) - ux, ey = approx_of(v.y) - uy;
    for (int k = 0; k < 2; ++k) {
      const Interval o = ex * (part.y[k] - uy) - ey * (part.x[k] - ux);
      if (turn(f) > 0 ? !(o.inf() > 0) : !(o.sup() < 0)) return false;
    }
  }
  return true;
}

// A curve whose part in the cell lies strictly inside one facet listed there,
// planar and strictly nearer at both its ends, is hidden throughout the cell:
// no cut or crossing there changes what is seen (7a-ii). (A cell's blocker
// covers the whole cell; such a facet covers only the curve's part.) Planar,
// as a blocker: the edges of its own face lie in its plane, never behind it.
// Its crossings with other curves there need no point: where one in front of
// it crosses, that facet is in front of the curve's own facets nearby, which
// then change nothing beside the one in front; one behind it is hidden there.
// Decided on the images' intervals, which never narrow, and exact predicates:
// the same on every thread count.
bool hidden_in_cell(const Curve& cv, const Cell& cell, const std::array<Corner, 4>& c, const ScreenScene& ss) {
  const double znear = std::max(approx_of(cv.s->z).sup(), approx_of(cv.t->z).sup());
  CellPart part;
  CGAL::Bbox_2 box;
  bool clipped = false;   // (the part made for the first facet that may hide it)
  for (int fi : cell.facets) {
    const Facet& f = ss.facet(fi);
    if (!f.planar || !f.occluder || f.zlo >= znear) continue;   // (not nearer anywhere)
    if (!clipped) {
      if (!part_in_cell(cv, c, part)) return false;
      box = part.box();
      clipped = true;
    }
    if (!(f.box.xmin() < box.xmin() && box.xmax() < f.box.xmax() && f.box.ymin() < box.ymin() &&
          box.ymax() < f.box.ymax()))
      continue;
    if (part_inside(f, part) && curve_behind(cv, f, ss.world)) return true;
  }
  return false;
}

// Whether the segment s-t meets each closed cell x0..x1 of row iy (their boxes
// are known to meet its box): not all four corners strictly on one side of its
// line. The corners' orientations, for the whole row at once (under upward
// rounding): neighbouring cells share two corners, and the end points'
// intervals are read once; each is orientation()'s interval expression, the
// exact sign only where it cannot tell. (Four orientations per cell were 4-8 %
// of a view of a mesh, or of squares seen obliquely, where a slanted edge's box
// holds many cells it misses.)
class RowCorners {
 public:
  RowCorners(const P3& s, const P3& t, const Grid& g, int x0, int x1, int iy) : s_(s), t_(t), x0_(x0) {
    const Interval sx = approx_of(s.x), sy = approx_of(s.y), dx = approx_of(t.x) - sx, dy = approx_of(t.y) - sy;
    // (dx (y - sy) - dy (x - sx): the first product is the row's, the second the column's.)
    const Interval below = dx * (g.Y[iy] - sy), above = dx * (g.Y[iy + 1] - sy);
    for (int ix = x0; ix <= x1 + 1; ++ix) {
      const Interval across = dy * (g.X[ix] - sx);
      bottom_.push_back(sign_at(below - across, Corner{g.X[ix], g.Y[iy]}));
      top_.push_back(sign_at(above - across, Corner{g.X[ix], g.Y[iy + 1]}));
    }
  }
  bool meets(int ix) const {
    const auto j = static_cast<std::size_t>(ix - x0_);
    const CGAL::Sign first = bottom_[j];
    return first == CGAL::ZERO || bottom_[j + 1] != first || top_[j + 1] != first || top_[j] != first;
  }

 private:
  CGAL::Sign sign_at(const Interval& value, const Corner& p) const {
    const auto known = sign_of(value);
    if (!known) return orientation(s_, t_, p);   // (counted there)
    ++filter_counts.calls;
    return *known;
  }
  const P3 &s_, &t_;
  int x0_;
  SmallVec<CGAL::Sign, 8> bottom_, top_;
};

// Where coordinate v falls among an axis's cells, as a fraction of the axis
// (0 at its first boundary, 1 at its last): the grid's own coordinates, in which
// every cell has the same size.
double warped(const Axis& a, double v) {
  const int i = a.index(v);
  const double w = a[i + 1] - a[i];
  return (i + std::clamp((v - a[i]) / w, 0.0, 1.0)) / a.cells();
}

// The curves' boxes, by index: the curves made, then the latent ones.
std::size_t curve_count(const ScreenScene& ss) { return ss.curves.size() + ss.latent_piece.size(); }
CGAL::Bbox_2 curve_box(const ScreenScene& ss, std::size_t i) {
  return i < ss.curves.size() ? ss.curves[i].box : latent_box(ss, i - ss.curves.size());
}

// A facet's share of the depth complexity: its projected area in the grid's own
// coordinates (doubles: it only sizes the grid), scaled by how its bounding box
// is stretched there; 0 for a facet that hides nothing.
double facet_area(const ScreenScene& ss, std::size_t fi, const Axis& X, const Axis& Y) {
  const FacetBrief& f = ss.brief(fi);
  if (!f.occluder) return 0;
  const SmallVec<const P3*, 4> v = corners_of(ss, fi);   // (its Facet may not be made yet)
  const std::size_t n = v.size();
  if (n == 0) return 0;
  auto xy = [&](std::size_t k) { return std::array<Interval, 2>{ss.x_of(*v[k]), ss.y_of(*v[k])}; };   // (each read once)
  double a = 0;
  CGAL::Bbox_2 box = f.box;   // (a sparse scene's brief may have none yet: its corners')
  const bool boxed = box.xmin() <= box.xmax();
  const std::array<Interval, 2> first = xy(0);
  std::array<Interval, 2> p = first;
  for (std::size_t k = 0; k < n; ++k) {
    const std::array<Interval, 2> q = k + 1 < n ? xy(k + 1) : first;
    a += CGAL::to_double(p[0]) * CGAL::to_double(q[1]) - CGAL::to_double(q[0]) * CGAL::to_double(p[1]);
    if (!boxed) box += CGAL::Bbox_2(p[0].inf(), p[1].inf(), p[0].sup(), p[1].sup());
    p = q;
  }
  const double w = box.xmax() - box.xmin(), h = box.ymax() - box.ymin();
  if (!(w > 0 && h > 0)) return 0;
  const double sx = (warped(X, box.xmax()) - warped(X, box.xmin())) / w;
  const double sy = (warped(Y, box.ymax()) - warped(Y, box.ymin())) / h;
  return std::abs(a) / 2 * sx * sy;
}

// The depth complexity: the occluders' projected area over the screen's, both
// in the grid's own coordinates. It only sizes the grid (as L, measured on a
// sample of the curves): above 2^16 facets, from every s-th facet (they are in
// screen order: the sample spreads over the screen), scaled up; on the 10^6-
// triangle terrain, 4 % of a lines-only drawing's instructions went to the whole
// sum. Above 2^18 facets, a sample of 2^14 (each a cache miss or more: 2^16 of
// them took the terrain 13 ms; 2^14 tell its depth complexity within 1 %).
// Chunks of the sample in parallel, their sums added in chunk order: the same
// for every thread count.
std::size_t depth_sample_step(std::size_t nf) { return std::max<std::size_t>(1, nf > (1u << 18) ? nf >> 14 : nf >> 16); }
double depth_complexity(const ScreenScene& ss, const Axis& X, const Axis& Y, int threads) {
  const std::size_t nf = ss.facet_count(), step = depth_sample_step(nf);
  const int n = static_cast<int>((nf + step - 1) / step), size = 8192;
  std::vector<double> part(static_cast<std::size_t>(chunk_count(n, size)), 0);
  parallel_chunks(n, size, threads, [&](int c, Chunk r) {
    double sum = 0;
    for (int i = r.begin; i < r.end; ++i) sum += facet_area(ss, static_cast<std::size_t>(i) * step, X, Y);
    part[static_cast<std::size_t>(c)] = sum;
  });
  double area = 0;
  for (double a : part) area += a;
  if (step > 1) area *= static_cast<double>(nf) / n;
  return std::isfinite(area) ? area : 5;
}

// The mean length of the curves in the grid's own coordinates (Franklin's L),
// on a sample of them.
double mean_length(const ScreenScene& ss, const Axis& X, const Axis& Y) {
  const std::size_t n = curve_count(ss), step = std::max<std::size_t>(1, n / 4096);
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; i += step, ++count) {
    const CGAL::Bbox_2 b = curve_box(ss, i);
    sum += std::hypot(warped(X, b.xmax()) - warped(X, b.xmin()), warped(Y, b.ymax()) - warped(Y, b.ymin()));
  }
  return count ? sum / static_cast<double>(count) : 0;
}

// Up to B cells from lo to hi whose boundaries split the sorted values v into
// runs of about equal count: cells are small where the drawing is dense (far
// parts of a perspective view) and large where it is sparse (near parts). Each
// boundary lies halfway between two different values, so it seldom falls on a
// vertex. Strictly increasing doubles, the first and last lo and hi (exact).
std::vector<double> quantile_bounds(const std::vector<double>& v, int B, double lo, double hi) {
  std::vector<double> b{lo};
  const std::size_t m = v.size();
  for (int i = 1; i < B; ++i) {
    std::size_t j = std::max<std::size_t>(1, static_cast<std::size_t>(i) * m / static_cast<std::size_t>(B));
    while (j < m && v[j - 1] == v[j]) ++j;
    if (j >= m) break;
    const double x = v[j - 1] + (v[j] - v[j - 1]) / 2;
    if (x > b.back() && x < hi) b.push_back(x);
  }
  b.push_back(hi > b.back() ? hi : std::nextafter(b.back(), HUGE_VAL));
  return b;
}

// The curves' end point coordinates along x (y: false), sorted: a sample of
// about `want` values, taken evenly from the curves (which are in screen order).
std::vector<double> end_coordinates(const ScreenScene& ss, bool x, std::size_t want) {
  const std::size_t n = curve_count(ss), step = std::max<std::size_t>(1, 2 * n / std::max<std::size_t>(want, 1));
  std::vector<double> v;
  v.reserve(2 * n / step + 2);
  for (std::size_t i = 0; i < n; i += step) {
    const CGAL::Bbox_2 b = curve_box(ss, i);
    v.push_back(x ? b.xmin() : b.ymin());
    v.push_back(x ? b.xmax() : b.ymax());
  }
  std::sort(v.begin(), v.end());
  return v;
}

// The boxes of runs of Grid::kRun consecutive items of n, add(i, box) adding
// item i's to its run's (or not), chunks of runs in parallel.
template <class Add>
std::vector<CGAL::Bbox_2> run_boxes(int n, int threads, Add&& add) {
  const int runs = (n + Grid::kRun - 1) / Grid::kRun;
  std::vector<CGAL::Bbox_2> box(static_cast<std::size_t>(runs));   // (each empty)
  parallel_chunks(runs, 256, threads, [&](int, Chunk r) {
    for (int k = r.begin; k < r.end; ++k)
      for (int i = k * Grid::kRun; i < std::min(n, (k + 1) * Grid::kRun); ++i) add(i, box[static_cast<std::size_t>(k)]);
  });
  return box;
}

}  // namespace

Axis::Axis(std::vector<double> bounds) : bounds_(std::move(bounds)) {
  bins_ = 16 * cells();
  last_ = cells() - 1;
  // The bins span the cells' boundaries, or only their middle where a few
  // outer cells reach far (a close-up in perspective: the cells of the near
  // faces' images run to a thousand times the others' reach, and the rest
  // crowd into a few bins). The outer cells then lie in the end bins, found
  // there by halving. Whichever of the spans asks fewer halving steps, the
  // cells being of about equal use (they are cut at quantiles).
  // (Where the whole span leaves a step or two per cell, nothing to gain.)
  int built = 0, best = 0;
  double fewest = spread_over(0);
  if (fewest > 2.0 * cells())
    for (const int j : {cells() / 64, cells() / 16})
      if (j > built)
        if (const double steps = spread_over(built = j); steps < fewest) {
          fewest = steps;
          best = j;
        }
  if (best != built) spread_over(best);
  steps_ = fewest;
}

// The bins over boundaries j .. cells() - j, the end bins holding the cells
// beyond; returns the halving steps a lookup takes, summed over the cells.
double Axis::spread_over(int j) {
  const double lo = bounds_[static_cast<std::size_t>(j)], hi = bounds_[static_cast<std::size_t>(cells() - j)];
  lo_ = lo;
  bins_per_unit_ = hi > lo ? bins_ / (hi - lo) : 0;
  if (!std::isfinite(bins_per_unit_)) bins_per_unit_ = 0;
  first_.resize(static_cast<std::size_t>(bins_) + 1);
  int i = 0;
  for (int k = 0; k <= bins_; ++k) {
    const double start = lo + k / bins_per_unit_;
    while (i + 1 < cells() && bounds_[static_cast<std::size_t>(i) + 1] <= start) ++i;
    first_[static_cast<std::size_t>(k)] = i;
  }
  first_.front() = 0;
  first_.back() = last_;
  double steps = 0;
  for (int k = 0; k < bins_; ++k) {
    const int n = first_[static_cast<std::size_t>(k) + 1] - first_[static_cast<std::size_t>(k)];
    if (n > 0) steps += n * std::log2(n + 1.0);
  }
  return steps;
}

// Steps 2-4: B = c * min(sqrt(N), 1/L) cells per side over the projected scene.
// Franklin's cells are equal; here each axis is cut at quantiles of the curves'
// end points instead, so that the cells follow the drawing where projected sizes
// vary (a close-up in perspective: near faces thousands of times larger than far
// ones), and N, L and the depth complexity are measured in those coordinates.
Grid make_grid(ScreenScene& ss, double c, int threads, Stats& stats) {
  // The box of the curves and occluders: the union of the made curves' boxes
  // and of the boxes of runs of latent curves and of occluders (kept for step 5).
  // A sparse scene has no box for most facets nor for its latent curves: the
  // runs of facets (each latent curve lies on one) from the world instead.
  Grid g;
  if (ss.sparse()) {
    g.occluder_runs = world_run_boxes(ss, Grid::kRun, threads);
  } else {
    g.latent_runs = run_boxes(static_cast<int>(ss.latent_piece.size()), threads,
                              [&](int i, CGAL::Bbox_2& b) { b += latent_box(ss, static_cast<std::size_t>(i)); });
    g.occluder_runs = run_boxes(static_cast<int>(ss.facet_count()), threads, [&](int i, CGAL::Bbox_2& b) {
      if (ss.brief(i).occluder) b += ss.brief(i).box;
    });
  }
  CGAL::Bbox_2 box;   // (empty)
  for (const Curve& curve : ss.curves) box += curve.box;
  for (const auto* runs : {&g.latent_runs, &g.occluder_runs})
    for (const CGAL::Bbox_2& b : *runs) box += b;
  const bool any = box.xmin() <= box.xmax();
  if (!any) box = CGAL::Bbox_2(0, 0, 1, 1);
  // The curves the cells are sized for. A lines-only drawing's latent curves (not
  // drawn) are mostly never listed: they count for 1/25 each, so that the grid
  // stays coarse where only the facets fill it (their pair search and hiding
  // tests want a few dozen per cell; measured: the 10^6-triangle terrain at
  // crease 30, lines only, 12 % less time than with all counted; B 1044 -> 267,
  // 256 with c = 2.5).
  const double n = static_cast<double>(ss.curves.size()) + static_cast<double>(ss.latent_piece.size()) / 25;
  const bool sized = any && std::max(box.xmax() - box.xmin(), box.ymax() - box.ymin()) > 0 && n > 0;
  std::vector<double> xs, ys;
  if (sized) {
    // The grid's coordinates, from the finest grid the rule allows.
    const int finest = static_cast<int>(std::clamp(4 * std::sqrt(n), 1.0, 4096.0));
    parallel_for(2, threads, [&](int y) {
      (y ? ys : xs) = end_coordinates(ss, !y, 32 * static_cast<std::size_t>(finest));
    });
    const Axis X(quantile_bounds(xs, finest, box.xmin(), box.xmax()));
    const Axis Y(quantile_bounds(ys, finest, box.ymin(), box.ymax()));
    const double L = mean_length(ss, X, Y);   // mean curve length on a unit screen
    // Fine cells pay where many faces lie over each other (they let a blocking
    // face hide the rest cell by cell) and cost memory and bookkeeping where few
    // do: a mesh seen from outside, a terrain. c is scaled by sqrt(D / 5), within
    // [1/4, 1], D the depth complexity. The default c = 2.5 (Options::grid_c):
    // counted in instructions, one thread, against c = 4: 10^4 random squares
    // (D 3.6) along an axis -4 %, obliquely -1 %, in perspective -3 %; bunny00
    // -2 to -3 %; fandisk -8 to -15 %; a terrain of 44 402 triangles -2 to -4 %;
    // 20^3 boxes -2 to -5 %; the generated building (D 5.5, large faces: each
    // covered hundreds of cells) from outside -29 %, from inside -5 %. Smaller
    // c helps meshes a little more, random squares less.
    if (ss.sparse()) {   // (the sample's boxes and corners, made once: each is read several times)
      std::vector<char> sample(ss.facet_count(), 0);
      for (std::size_t fi = 0; fi < sample.size(); fi += depth_sample_step(sample.size())) sample[fi] = 1;
      make_boxes(ss, sample, threads);
    }
    const double D = depth_complexity(ss, X, Y, threads);
    c *= std::clamp(std::sqrt(D / 5), 0.25, 1.0);
    stats.count("depth_complexity_percent", static_cast<std::int64_t>(std::min(D, 1e9) * 100));
    const double b = c * std::min(std::sqrt(n), L > 0 ? 1 / L : std::sqrt(n));
    g.B = static_cast<int>(std::clamp(b, 1.0, 4096.0));
  }
  g.X = Axis(sized ? quantile_bounds(xs, g.B, box.xmin(), box.xmax()) : std::vector<double>{box.xmin(), box.xmax()});
  g.Y = Axis(sized ? quantile_bounds(ys, g.B, box.ymin(), box.ymax()) : std::vector<double>{box.ymin(), box.ymax()});
  g.cells.resize(static_cast<std::size_t>(g.X.cells()) * g.Y.cells());
  stats.count("grid_B", g.B);
  stats.count("grid_columns", g.X.cells());
  stats.count("grid_rows", g.Y.cells());
  stats.count("grid_cells", static_cast<std::int64_t>(g.cells.size()));
  return g;
}

namespace {

// No rows (an item left out of items_by_row).
constexpr std::array<int, 2> kNoRows{1, 0};

// The items (facets or curves, by index, in index order) whose box reaches each
// row of cells, side by side: row r's are items[first[r] .. first[r + 1]). The
// rows then fill their cells in parallel: a cell sees its items in index order,
// as one pass over the items in order would give them.
struct ItemsByRow {
  std::vector<std::size_t> first;
  std::vector<int> items;
  std::size_t size() const { return first.size() - 1; }
  std::span<const int> operator[](std::size_t r) const { return {items.data() + first[r], first[r + 1] - first[r]}; }
};

// Chunks of items in parallel: each item's rows and each chunk's count per row;
// then each chunk writes its items at its place in every row.
template <class RowsOf>
ItemsByRow items_by_row(const Grid& g, int n, int threads, RowsOf&& rows_of) {
  const int nrows = g.Y.cells(), size = 16384, chunks = chunk_count(n, size);
  std::vector<std::array<int, 2>> span(static_cast<std::size_t>(n));   // rows y0 .. y1 (y0 > y1: none)
  std::vector<std::vector<std::size_t>> at(static_cast<std::size_t>(chunks));   // per chunk and row: count, then place
  parallel_chunks(n, size, threads, [&](int c, Chunk r) {
    std::vector<std::size_t>& count = at[static_cast<std::size_t>(c)];
    count.assign(static_cast<std::size_t>(nrows), 0);
    for (int i = r.begin; i < r.end; ++i) {
      const auto [y0, y1] = span[static_cast<std::size_t>(i)] = rows_of(i);
      for (int iy = y0; iy <= y1; ++iy) ++count[static_cast<std::size_t>(iy)];
    }
  });
  ItemsByRow rows;
  rows.first.assign(static_cast<std::size_t>(nrows) + 1, 0);
  std::size_t total = 0;
  for (std::size_t r = 0; r < static_cast<std::size_t>(nrows); ++r) {
    rows.first[r] = total;
    for (std::vector<std::size_t>& count : at) {
      const std::size_t k = count[r];
      count[r] = total;
      total += k;
    }
  }
  rows.first[static_cast<std::size_t>(nrows)] = total;
  rows.items.resize(total);
  parallel_chunks(n, size, threads, [&](int c, Chunk r) {
    std::vector<std::size_t>& place = at[static_cast<std::size_t>(c)];
    for (int i = r.begin; i < r.end; ++i) {
      const auto [y0, y1] = span[static_cast<std::size_t>(i)];
      for (int iy = y0; iy <= y1; ++iy) rows.items[place[static_cast<std::size_t>(iy)]++] = i;
    }
  });
  return rows;
}

// Marks, after a parallel pass over rows, the items some row kept.
void mark_kept(std::vector<std::vector<int>>& kept_by_row, std::vector<char>& kept) {
  for (auto& row : kept_by_row) {
    for (int i : row) kept[static_cast<std::size_t>(i)] = 1;
    std::vector<int>().swap(row);
  }
}

// Whether the corners of the cells of row iy lie strictly inside facet f's
// projection (strictly_inside), each corner asked once, when first needed:
// neighbouring cells share two. (Four per cell were a tenth of a view of the
// generated building, whose walls and slabs cover many cells each.)
class InsideCorners {
 public:
  InsideCorners(const Facet& f, const Grid& g, int x0, int x1, int iy) : f_(f), g_(g), x0_(x0), x1_(x1), iy_(iy) {}
  // All four corners of cell ix strictly inside, asked in corners()'s order.
  bool all(int ix) {
    return inside(ix, 0) && inside(ix + 1, 0) && inside(ix + 1, 1) && inside(ix, 1);
  }

 private:
  static constexpr signed char kUnknown = -1;
  bool inside(int column, int top) {
    // (Made at the first question: a mesh's small facets rarely hold a whole cell.)
    if (known_.empty()) known_.assign(2 * static_cast<std::size_t>(x1_ - x0_ + 2), kUnknown);
    signed char& k = known_[2 * static_cast<std::size_t>(column - x0_) + static_cast<std::size_t>(top)];
    if (k == kUnknown) k = strictly_inside(f_, Corner{g_.X[column], g_.Y[iy_ + top]}) ? 1 : 0;
    return k != 0;
  }
  const Facet& f_;
  const Grid& g_;
  int x0_, x1_, iy_;
  std::vector<signed char> known_;
};

// Step 5 for facet fi in cell (ix, iy): listed, made the blocker, or skipped as
// hidden by the blocker there. True if the facet is kept in the cell.
bool bucket_facet(Grid& g, const ScreenScene& ss, int fi, int ix, int iy, InsideCorners& inside,
                  std::int64_t& skipped, std::int64_t& blockers) {
  const Facet& f = ss.facet(fi);
  Cell& cell = g.at(ix, iy);
  auto c = corners(g, ix, iy);
  if (cell.blocker >= 0 && behind_throughout(f, ss.facet(cell.blocker), c)) { ++skipped; return false; }
  // Only a planar polygon's facet may block: the edges of its own face lie in
  // its plane, so what is behind it cannot hide them. A non-planar polygon's
  // fan piece can be in front of its own face's edge while another face,
  // behind the piece, still hides that edge (no face hides its own edges).
  // (A corner strictly inside the facet lies inside its box: a cell the box does
  // not hold is not covered, told without a predicate. Most are not, on a mesh.)
  const bool boxed = f.box.xmin() <= c[0].x && c[2].x <= f.box.xmax() && f.box.ymin() <= c[0].y && c[2].y <= f.box.ymax();
  bool covers = f.planar && boxed && inside.all(ix);
  if (!covers) { cell.facets.push_back(fi); return true; }
  ++blockers;
  if (cell.blocker < 0 || behind_throughout(ss.facet(cell.blocker), f, c)) { cell.blocker = fi; return true; }
  // Two covering facets that cross inside the cell: the nearer at the centre
  // blocks, the other stays listed.
  P2 mid(FT(g.X[ix] + g.X[ix + 1]) / 2, FT(g.Y[iy] + g.Y[iy + 1]) / 2);
  const Facet& b = ss.facet(cell.blocker);
  bool nearer = f.depth_at(mid) < b.depth_at(mid) || (f.depth_at(mid) == b.depth_at(mid) && f.face < b.face);
  if (nearer) { cell.facets.push_back(cell.blocker); cell.blocker = fi; }
  else cell.facets.push_back(fi);
  return true;
}

}  // namespace

namespace {

// Marked cells (a char per cell, row-major), and whether a range of cells holds
// one, in four reads: a summed-area table.
class MarkedCells {
 public:
  MarkedCells(const Grid& g, const std::vector<char>& mark)
      : columns_(g.X.cells() + 1), sum_(static_cast<std::size_t>(columns_) * (g.Y.cells() + 1), 0) {
    const int nx = g.X.cells(), ny = g.Y.cells();
    for (int y = 0; y < ny; ++y) {
      std::uint32_t row = 0;   // marks in cells (0 .. x, y)
      for (int x = 0; x < nx; ++x) {
        row += mark[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(x)] != 0;
        at(x + 1, y + 1) = at(x + 1, y) + row;
      }
    }
  }
  bool any(const CellRange& r) const {
    return r.x0 <= r.x1 && r.y0 <= r.y1 && at(r.x1 + 1, r.y1 + 1) - at(r.x0, r.y1 + 1) - at(r.x1 + 1, r.y0) + at(r.x0, r.y0) != 0;
  }
  // Whether the cells of box b (empty: none) hold one.
  bool any(const Grid& g, const CGAL::Bbox_2& b) const { return b.xmin() <= b.xmax() && any(range_of(g, b)); }

 private:
  // Marks in the cells [0, x) x [0, y) (modulo 2^32: differences are exact).
  std::uint32_t& at(int x, int y) { return sum_[static_cast<std::size_t>(y) * columns_ + static_cast<std::size_t>(x)]; }
  std::uint32_t at(int x, int y) const { return sum_[static_cast<std::size_t>(y) * columns_ + static_cast<std::size_t>(x)]; }
  std::size_t columns_;
  std::vector<std::uint32_t> sum_;
};

// The cells steps 5-11 may look at, for a lines-only drawing where no two faces
// pierce each other (one solid or height field: no intersection line can start
// a drawn line anywhere), or none (empty: every cell). A curve is listed in a
// cell only if its box reaches a cell a drawn curve's box reaches (a drawn curve;
// one made late beside it; one cut_curves finds needed, listed then in every cell
// it reaches): the candidates. What is looked at is the cells of their boxes and
// of their facets' boxes, each filled as the whole grid's would be (every facet
// reaching it, in index order); their facets (`whole`: every cell of theirs looked
// at) are the only ones whose step 5c is taken, and the only ones whose flag
// cut_curves reads (a listed curve's sharers). `latent_near` marks the candidates
// among the latent curves (Grid::latent_near).
struct DrawingCells {
  std::vector<char> cell;          // per cell: looked at
  std::vector<char> whole;         // per facet
  std::vector<char> latent_near;   // per latent curve
  bool all() const { return cell.empty(); }
};
DrawingCells drawing_cells(const Grid& g, ScreenScene& ss, bool regions, int threads) {
  DrawingCells d;
  const std::vector<WorldPiece>* pieces = latent_pieces_of(ss);
  if (regions || !occluders_in_one_solid(ss) || (!ss.latent_piece.empty() && !pieces)) return d;
  const auto nx = static_cast<std::size_t>(g.X.cells());
  auto each_cell = [&](const CellRange& r, auto&& f) {
    for (int iy = r.y0; iy <= r.y1; ++iy)
      for (int ix = r.x0; ix <= r.x1; ++ix) f(static_cast<std::size_t>(iy) * nx + static_cast<std::size_t>(ix));
  };
  std::vector<char> drawn(g.cells.size(), 0);
  for (const Curve& c : ss.curves)
    if (c.drawn) each_cell(range_of(g, c.box), [&](std::size_t k) { drawn[k] = 1; });
  const MarkedCells near_drawn(g, drawn);
  // The candidates' sharers, and the candidates' cells.
  d.whole.assign(ss.facet_count(), 0);
  d.cell.assign(g.cells.size(), 0);
  for (const Curve& c : ss.curves) {
    const CellRange r = range_of(g, c.box);
    if (!near_drawn.any(r)) continue;
    each_cell(r, [&](std::size_t k) { d.cell[k] = 1; });
    for (int f : c.sharers) d.whole[static_cast<std::size_t>(f)] = 1;
  }
  // The latent candidates, from the runs whose box reaches a drawn curve's cell
  // (a curve's cells lie within its run's).
  d.latent_near.assign(ss.latent_piece.size(), 0);
  const int n = static_cast<int>(ss.latent_piece.size()), runs = static_cast<int>(g.latent_runs.size());
  std::vector<std::vector<std::pair<int, CellRange>>> found(static_cast<std::size_t>(chunk_count(runs, 256)));
  // (A sparse scene's: from the runs of facets, the run of a latent curve's
  // first sharer, on which it lies.)
  // Their facets' boxes are made first (step 5 makes those of every run near
  // the cells it looks at, these among them): a latent curve lies on its facet,
  // within its box.
  std::vector<char> facet_run_near;
  if (ss.sparse()) {
    facet_run_near.resize(g.occluder_runs.size());
    for (std::size_t run = 0; run < facet_run_near.size(); ++run) facet_run_near[run] = near_drawn.any(g, g.occluder_runs[run]);
    std::vector<char> which(ss.facet_count());
    for (std::size_t fi = 0; fi < which.size(); ++fi) which[fi] = facet_run_near[fi / Grid::kRun];
    make_boxes(ss, which, threads);
  }
  auto take = [&](int i, std::vector<std::pair<int, CellRange>>& here) {
    const CellRange range = range_of(g, latent_box(ss, static_cast<std::size_t>(i)));
    if (near_drawn.any(range)) here.emplace_back(i, range);
  };
  parallel_chunks(runs, 256, threads, [&](int k, Chunk r) {
    std::vector<std::pair<int, CellRange>> here;   // (filled here, stored once)
    for (int run = r.begin; run < r.end; ++run) {
      if (!near_drawn.any(g, g.latent_runs[static_cast<std::size_t>(run)])) continue;
      for (int i = run * Grid::kRun; i < std::min(n, (run + 1) * Grid::kRun); ++i) take(i, here);
    }
    found[static_cast<std::size_t>(k)] = std::move(here);
  });
  if (ss.sparse()) {
    found.assign(static_cast<std::size_t>(chunk_count(n, 16384)), {});
    parallel_chunks(n, 16384, threads, [&](int k, Chunk r) {
      std::vector<std::pair<int, CellRange>> here;
      for (int i = r.begin; i < r.end; ++i) {
        const int first = (*pieces)[static_cast<std::size_t>(ss.latent_piece[static_cast<std::size_t>(i)])].sharers[0].facet;
        if (!facet_run_near[static_cast<std::size_t>(first / Grid::kRun)]) continue;
        const CGAL::Bbox_2& box = ss.brief(static_cast<std::size_t>(first)).box;   // (none: edge-on)
        if (box.xmin() <= box.xmax() && !near_drawn.any(g, box)) continue;
        take(i, here);
      }
      found[static_cast<std::size_t>(k)] = std::move(here);
    });
  }
  for (const auto& here : found)
    for (const auto& [i, range] : here) {
      d.latent_near[static_cast<std::size_t>(i)] = 1;
      each_cell(range, [&](std::size_t k) { d.cell[k] = 1; });
      for (const Sharer& s : (*pieces)[static_cast<std::size_t>(ss.latent_piece[static_cast<std::size_t>(i)])].sharers)
        d.whole[static_cast<std::size_t>(s.facet)] = 1;
    }
  make_boxes(ss, d.whole, threads);   // (a sparse scene's, where not made yet)
  for (std::size_t f = 0; f < d.whole.size(); ++f)
    if (d.whole[f]) each_cell(range_of(g, ss.brief(f).box), [&](std::size_t k) { d.cell[k] = 1; });
  return d;
}

// Each facet's cells (those of its box; the hull of its corners' cells, where
// they are images, is the same: Axis::index is monotone), for step 5 and the
// pair search. Where only some cells are looked at (`looked`), only the
// occluders' in runs whose box reaches one of them (no other is listed; the
// rest: no cells).
std::vector<CellRange> facet_ranges(const Grid& g, ScreenScene& ss, const MarkedCells* looked, int threads) {
  const int nf = static_cast<int>(ss.facet_count());
  std::vector<CellRange> range(ss.facet_count());
  if (looked) {
    const int runs = static_cast<int>(g.occluder_runs.size());
    std::vector<char> near(static_cast<std::size_t>(runs));
    parallel_chunks(runs, 256, threads, [&](int, Chunk r) {
      for (int run = r.begin; run < r.end; ++run) near[static_cast<std::size_t>(run)] = looked->any(g, g.occluder_runs[static_cast<std::size_t>(run)]);
    });
    if (ss.sparse()) {   // (their boxes, where not made yet)
      std::vector<char> which(ss.facet_count(), 0);
      for (int fi = 0; fi < nf; ++fi) which[static_cast<std::size_t>(fi)] = near[static_cast<std::size_t>(fi / Grid::kRun)];
      make_boxes(ss, which, threads);
    }
    parallel_chunks(runs, 256, threads, [&](int, Chunk r) {
      for (int run = r.begin; run < r.end; ++run) {
        const bool near_here = near[static_cast<std::size_t>(run)];
        for (int fi = run * Grid::kRun; fi < std::min(nf, (run + 1) * Grid::kRun); ++fi)
          range[static_cast<std::size_t>(fi)] = near_here && ss.brief(fi).occluder ? range_of(g, ss.brief(fi).box) : CellRange{0, -1, 0, -1};
      }
    });
    return range;
  }
  const ImageCells image_cells(g, ss, threads);   // (four lookups per image instead of four per facet)
  parallel_chunks(nf, 4096, threads, [&](int, Chunk r) {
    for (int fi = r.begin; fi < r.end; ++fi) {
      CellRange& here = range[static_cast<std::size_t>(fi)];
      if (const Facet* f = ss.made_facet(static_cast<std::size_t>(fi))) {
        if (!image_cells.hull(f->v, f->v.size(), here)) here = range_of(g, f->box);
        continue;
      }
      const SmallVec<const P3*, 4> v = corners_of(ss, static_cast<std::size_t>(fi));
      if (!image_cells.hull(v, v.size(), here)) here = range_of(g, ss.brief(static_cast<std::size_t>(fi)).box);
    }
  });
  return range;
}

}  // namespace

// Step 5: each facet goes to the cells of its bounding box, unless the cell's
// blocking facet hides it there; a facet covering a cell may become its blocker.
// Rows of cells in parallel. (A lines-only drawing may need only some cells:
// drawing_cells.)
void bucket_facets(Grid& g, ScreenScene& ss, bool regions, int threads, Stats& stats) {
  const int nf = static_cast<int>(ss.facet_count());
  DrawingCells only = drawing_cells(g, ss, regions, threads);
  g.latent_near = std::move(only.latent_near);
  auto looked_at = [&](int ix, int iy) { return only.all() || only.cell[static_cast<std::size_t>(iy) * g.X.cells() + ix]; };
  const std::optional<MarkedCells> looked = only.all() ? std::nullopt : std::optional<MarkedCells>(std::in_place, g, only.cell);
  g.facet_range = facet_ranges(g, ss, looked ? &*looked : nullptr, threads);
  std::vector<char> listed(ss.facet_count(), 0);
  const ItemsByRow rows = items_by_row(g, nf, threads, [&](int fi) {
    const CellRange& r = g.facet_range[static_cast<std::size_t>(fi)];
    listed[static_cast<std::size_t>(fi)] = ss.brief(static_cast<std::size_t>(fi)).occluder && (!looked || looked->any(r));
    return listed[static_cast<std::size_t>(fi)] ? std::array<int, 2>{r.y0, r.y1} : kNoRows;
  });
  // The images of what steps 5-11 may read (where they are left for later: a
  // lines-only drawing's), the listed facets' and those of the candidates'
  // sharers; then the depth planes of what is listed (and only of that, for a
  // lines-only drawing).
  // (Their Facets first, where only briefs were kept: make_facets.)
  if (only.all()) {
    make_facets(ss, {}, threads);
    make_corner_images(ss, {}, threads);
  } else {
    std::vector<char> read(listed);
    for (std::size_t fi = 0; fi < read.size(); ++fi) read[fi] |= only.whole[fi];
    make_facets(ss, read, threads);
    make_corner_images(ss, read, threads);
  }
  if (ss.planes_later) make_depth_planes(ss, listed, threads);
  std::vector<std::vector<int>> kept_by_row(rows.size());
  std::vector<std::array<std::int64_t, 2>> counts(rows.size());   // skipped, blockers
  parallel_for(g.Y.cells(), threads, [&](int iy) {
    UpwardRounding upward;   // the corner tests are our own filtered predicates
    const auto row = static_cast<std::size_t>(iy);
    std::int64_t skipped = 0, blockers = 0;   // (counted here, stored once: rows side by side share cache lines)
    std::vector<int> kept_here;
    for (int fi : rows[row]) {
      const CellRange& r = g.facet_range[static_cast<std::size_t>(fi)];
      bool kept = false;
      InsideCorners inside(ss.facet(fi), g, r.x0, r.x1, iy);
      for (int ix = r.x0; ix <= r.x1; ++ix)
        if (looked_at(ix, iy)) kept |= bucket_facet(g, ss, fi, ix, iy, inside, skipped, blockers);
      if (kept) kept_here.push_back(fi);
    }
    kept_by_row[row] = std::move(kept_here);
    counts[row] = {skipped, blockers};
  });
  std::vector<char> kept(ss.facet_count(), 0);
  mark_kept(kept_by_row, kept);
  std::int64_t hidden_facets = 0, skipped = 0, blockers = 0;
  for (std::size_t fi = 0; fi < ss.facet_count(); ++fi) {
    const bool known = only.all() || only.whole[fi];   // (every cell of it looked at)
    if (ss.brief(fi).occluder && known && !kept[fi]) { ss.set_occluder(fi, false); ++hidden_facets; }   // step 5c
  }
  for (const auto& c : counts) {
    skipped += c[0];
    blockers += c[1];
  }
  stats.count("facet_cells_behind_blocker", skipped);
  stats.count("blocking_candidates", blockers);
  stats.count("culled_behind_blocking_face", hidden_facets);
  if (!only.all())
    stats.count("cells_for_drawn_lines", std::count(only.cell.begin(), only.cell.end(), 1));
  if (ss.lean()) stats.count("facets_made", static_cast<std::int64_t>(ss.facets.size()));
}

// Step 6: drop what the final blocker hides (it may have changed after a facet
// was listed). Rows of cells in parallel.
void prune_facets(Grid& g, const ScreenScene& ss, int threads, Stats& stats) {
  std::vector<std::int64_t> pruned_by_row(static_cast<std::size_t>(g.Y.cells()), 0);
  parallel_for(g.Y.cells(), threads, [&](int iy) {
    UpwardRounding upward;
    std::int64_t pruned = 0;   // (counted here, stored once: rows side by side share cache lines)
    for (int ix = 0; ix < g.X.cells(); ++ix) {
      Cell& cell = g.at(ix, iy);
      if (cell.blocker < 0) continue;
      auto c = corners(g, ix, iy);
      const Facet& b = ss.facet(cell.blocker);
      auto hidden = [&](int fi) { return fi == cell.blocker || behind_throughout(ss.facet(fi), b, c); };
      std::size_t before = cell.facets.size();
      cell.facets.erase(std::remove_if(cell.facets.begin(), cell.facets.end(), hidden), cell.facets.end());
      pruned += static_cast<std::int64_t>(before - cell.facets.size());
    }
    pruned_by_row[static_cast<std::size_t>(iy)] = pruned;
  });
  std::int64_t pruned = 0;
  for (std::int64_t p : pruned_by_row) pruned += p;
  stats.count("facet_cells_pruned", pruned);
}

namespace {

// Whether canonical vertices u and v are the ends of an edge of facet F.
bool has_edge(const Facet& F, long u, long v) {
  const std::size_t n = F.id.size();
  for (std::size_t k = 0; k < n; ++k) {
    const long p = F.id[k], q = F.id[(k + 1) % n];
    if ((p == u && q == v) || (p == v && q == u)) return true;
  }
  return false;
}

// Whether canonical vertices u and v are the ends of an edge of both facets.
bool common_edge(const Facet& A, const Facet& B, long u, long v) { return has_edge(A, u, v) && has_edge(B, u, v); }

// The input's vertices of a facet that keeps them all (not cut at the near
// plane): its corners by canonical id, or none.
bool input_corners(const Facet& F) {
  return std::all_of(F.id.begin(), F.id.end(), [](long v) { return v >= 0; });
}

// Newell's tests 3 and 4: whether every corner k of F that G lacks (a shared
// corner lies in G's plane, known without arithmetic) is on one closed side of
// G's plane, side(k) its sign there.
template <class Side>
bool on_one_side(const Facet& F, const Facet& G, Side&& side) {
  bool pos = false, neg = false;
  for (std::size_t k = 0; k < F.id.size(); ++k) {
    if (G.has_vertex(F.id[k])) continue;
    const int s = side(k);
    pos |= s > 0;
    neg |= s < 0;
  }
  return !(pos && neg);
}

// The same in the world, on the input's doubles, for a triangle G. A projection
// (parallel, or central for points in front of the eye) maps G's plane to its
// screen plane and keeps each side of it on one side, so the answer is the screen's.
bool one_side_in_world(const Facet& F, const Facet& G, const std::vector<Vec3>& world) {
  const world::PlaneSide side(vertex_at(world, G.id[0]), vertex_at(world, G.id[1]), vertex_at(world, G.id[2]));
  return on_one_side(F, G, [&](std::size_t k) { return side(vertex_at(world, F.id[k])); });
}

// Whether triangle F (of a simple planar polygon) has a diagonal in G's plane:
// then, though on one side of it, the polygon may cross it there (meets_plane).
bool along_diagonal_in_world(const Facet& F, const Facet& G, const std::vector<Vec3>& world) {
  if (!F.may_cross_at_diagonal()) return false;
  const Vec3 &o = vertex_at(world, G.id[0]), &a = vertex_at(world, G.id[1]), &b = vertex_at(world, G.id[2]);
  auto on_plane = [&](std::size_t k) {
    return G.has_vertex(F.id[k]) || world::orientation(o, a, b, vertex_at(world, F.id[k])) == 0;
  };
  for (std::size_t k = 0; k < 3; ++k)
    if (F.on_diagonal(k) && on_plane(k) && on_plane((k + 1) % 3)) return true;
  return false;
}

// Triangles A = (v, a1, a2) and B = (v, b1, b2) that share only corner v and
// each cross the other's plane (the corners they do not share strictly on both
// sides): each meets the line where the planes meet in a segment from v, A's
// towards a point strictly inside a1-a2. They meet only at v if B's segment
// leaves v the other way: if B's crossing of A's plane lies on the other side of
// the line v-a1 than a2 does (told as sides of the plane through v, a1, b1).
bool meet_only_at_shared_corner(const Facet& A, const Facet& B, const std::vector<Vec3>& world) {
  auto at = [&](long id) -> const Vec3& { return vertex_at(world, id); };
  int k = 0;
  while (k < 3 && !B.has_vertex(A.id[k])) ++k;
  if (k == 3) return false;
  const long v = A.id[k];
  const Vec3 &pv = at(v), &a1 = at(A.id[(k + 1) % 3]), &a2 = at(A.id[(k + 2) % 3]);
  int j = 0;
  while (B.id[j] != v) ++j;
  const Vec3 &b1 = at(B.id[(j + 1) % 3]), &b2 = at(B.id[(j + 2) % 3]);
  const int crossing = world::orientation(pv, a1, b1, b2), other = world::orientation(pv, a1, b1, a2);
  return crossing != 0 && other != 0 && crossing != other;
}

// Whether facets A and B, both keeping their input corners, lie in boxes of the
// world that do not meet: then they share no point (their corners are the
// input's doubles, so the boxes are exact). Facets of separate objects that
// overlap on the screen and in depth, as the buildings of a city seen from
// above, are told apart here with no arithmetic.
bool boxes_apart_in_world(const Facet& A, const Facet& B, const std::vector<Vec3>& world) {
  if (!input_corners(A) || !input_corners(B)) return false;
  auto box = [&](const Facet& F) {
    std::array<double, 6> b{HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (const long v : F.id) {
      const Vec3& p = vertex_at(world, v);
      b = {std::min(b[0], p.x), std::min(b[1], p.y), std::min(b[2], p.z),
           std::max(b[3], p.x), std::max(b[4], p.y), std::max(b[5], p.z)};
    }
    return b;
  };
  const std::array<double, 6> a = box(A), b = box(B);
  return a[3] < b[0] || b[3] < a[0] || a[4] < b[1] || b[4] < a[1] || a[5] < b[2] || b[5] < a[2];
}

// Whether triangles A and B, both keeping their input corners, are proved on the
// input's doubles to have no crossing (most pairs a grid offers on a mesh are
// neighbours, apart). False: not proved.
bool apart_in_world(const Facet& A, const Facet& B, const std::vector<Vec3>& world) {
  if (A.id.size() != 3 || B.id.size() != 3 || !input_corners(A) || !input_corners(B)) return false;
  if ((one_side_in_world(A, B, world) && !along_diagonal_in_world(A, B, world)) ||
      (one_side_in_world(B, A, world) && !along_diagonal_in_world(B, A, world)))
    return true;
  // Each crosses the other's plane strictly (a shared corner lies in both).
  return meet_only_at_shared_corner(A, B, world);
}

// How facet F meets the plane of facet G (side(k): the sign of F's corner k):
// Cross, corners strictly on both sides; AlongDiagonal, on the positive side and
// touching the plane along a diagonal of the simple planar polygon F splits
// (`diagonal`: its index): the polygon goes on past it to the negative side, so it crosses the
// plane there (the facet across the diagonal, on the negative side, reports
// nothing, so the crossing is found once); otherwise Apart (Newell's tests 3
// and 4: on one side, touching or not).
enum class Meets { Apart, Cross, AlongDiagonal };
template <class Side>
Meets meets_plane(const Facet& F, const Facet& G, Side&& side, std::size_t& diagonal) {
  // (A fan's pieces need not lie on either side of a diagonal: only Newell's tests.)
  if (!F.may_cross_at_diagonal()) return on_one_side(F, G, side) ? Meets::Apart : Meets::Cross;
  const std::size_t n = F.id.size();   // (a triangle, cut or not: n <= 4)
  int sign[8];
  bool positive = false, negative = false;
  for (std::size_t k = 0; k < n; ++k) {   // each corner's side once
    sign[k] = G.has_vertex(F.id[k]) ? 0 : side(k);
    positive |= sign[k] > 0;
    negative |= sign[k] < 0;
  }
  if (positive && negative) return Meets::Cross;
  for (std::size_t k = 0; k < n && positive; ++k)
    if (F.on_diagonal(k) && sign[k] == 0 && sign[(k + 1) % n] == 0) {
      diagonal = k;
      return Meets::AlongDiagonal;
    }
  return Meets::Apart;
}

}  // namespace

bool intersection_segment(const Facet& A, const Facet& B, const std::vector<Vec3>* world, P2& p, P2& q) {
  // Most pairs a grid offers are neighbours on a mesh, or parts of separate
  // objects, apart: told on doubles.
  if (world && (boxes_apart_in_world(A, B, *world) || apart_in_world(A, B, *world))) return false;
  auto meets = [&](const Facet& F, const Facet& G, std::size_t& diagonal) {
    return meets_plane(F, G, [&](std::size_t k) { return static_cast<int>(depth_above(F.v[k], G, world, F.id[k])); },
                       diagonal);
  };
  std::size_t diagonal[2] = {SIZE_MAX, SIZE_MAX};   // A's and B's, where one lies along the crossing line
  if (meets(A, B, diagonal[0]) == Meets::Apart || meets(B, A, diagonal[1]) == Meets::Apart) return false;
  // Corners the two share (by identity) lie on both planes, so on their crossing
  // line. Two adjacent in both facets make it their common edge's line: nothing of
  // it is strictly inside either. One shared corner v: the line is parametrised
  // from v, and at A's and B's edges through v the parameter is 0 exactly.
  long shared = -1;
  for (std::size_t k = 0; k < A.v.size(); ++k)
    if (B.has_vertex(A.id[k])) {
      if (shared >= 0 && common_edge(A, B, shared, A.id[k])) return false;
      shared = A.id[k];
    }
  FT da = A.plane->number(0) - B.plane->number(0), db = A.plane->number(1) - B.plane->number(1),
     dc = A.plane->number(2) - B.plane->number(2);
  // The crossing line: da x + db y + dc = 0, as p0 + t d. (da, db) != (0, 0):
  // each facet has corners strictly on both sides of the other's plane, so the
  // planes are neither equal nor parallel.
  P2 p0;
  if (shared >= 0) {
    p0 = A.v[std::find(A.id.begin(), A.id.end(), shared) - A.id.begin()].xy();
  } else {
    // Any non-zero coefficient gives a point of the line; one whose interval
    // excludes zero is known to be non-zero without its exact value.
    const Interval ia = approx_of(da), ib = approx_of(db);
    const bool use_x = ia.inf() > 0 || ia.sup() < 0 ? true
                       : ib.inf() > 0 || ib.sup() < 0 ? false
                                                      : !CGAL::is_zero(da);
    p0 = use_x ? P2(-dc / da, FT(0)) : P2(FT(0), -dc / db);
  }
  V2 d(-db, da);
  bool has_lo = false, has_hi = false;
  FT lo{}, hi{};   // (set before use: has_lo, has_hi; {}: a double is zeroed, a lazy number shares its zero)
  for (const Facet* F : {&A, &B}) {
    const std::size_t n = F->v.size();
    for (std::size_t k = 0; k < n; ++k) {
      if (k == diagonal[F == &B]) continue;   // the line runs along it: the facet's other edges bound it
      const P2 &e0 = F->v[k].xy(), &e1 = F->v[(k + 1) % n].xy();
      V2 e = e1 - e0;
      const bool through_p0 = shared >= 0 && (F->id[k] == shared || F->id[(k + 1) % n] == shared);
      FT alpha = through_p0 ? FT(0) : e.x() * (p0.y() - e0.y()) - e.y() * (p0.x() - e0.x());
      FT beta = e.x() * d.y() - e.y() * d.x();
      if (turn(*F) < 0) { alpha = -alpha; beta = -beta; }
      auto sb = CGAL::sign(beta);
      if (sb == CGAL::ZERO) {
        if (through_p0 || !CGAL::is_positive(alpha)) return false;   // outside, or along the edge
        continue;
      }
      FT t = through_p0 ? FT(0) : FT(-alpha / beta);
      if (sb > 0) { if (!has_lo || t > lo) lo = t; has_lo = true; }
      else { if (!has_hi || t < hi) hi = t; has_hi = true; }
    }
  }
  if (!has_lo || !has_hi || !(lo < hi)) return false;
  p = p0 + lo * d;
  q = p0 + hi * d;
  return true;
}

Curve crossing_curve(const Facet& A, const Facet& B, int fa, int fb, const P2& p, const P2& q, std::deque<P3>& ends) {
  P3 s(p, A.depth_at(p)), t(q, A.depth_at(q));
  if (A.may_cross_at_diagonal() || B.may_cross_at_diagonal()) {
    for (const P3* e : {&s, &t}) {
      to_mpq(e->x);
      to_mpq(e->y);
      to_mpq(e->z);
    }
    return intersection_curve(s, t, fa, fb, A.face, B.face, ends);
  }
  return intersection_curve(frozen(s), frozen(t), fa, fb, A.face, B.face, ends);
}

namespace {

// Facets with an edge in common (by identity) meet only along it, or lie in one
// plane: they never pierce each other.
bool share_an_edge(const Facet& A, const Facet& B) {
  const std::size_t n = A.id.size();
  for (std::size_t k = 0; k < n; ++k) {
    const long p = A.id[k], q = A.id[(k + 1) % n];   // (an edge of A)
    if (p >= 0 && q >= 0 && has_edge(B, p, q)) return true;
  }
  return false;
}

// neighbours_apart for two triangles, from their corners a and b (-1: made by
// the near plane's cut). Two corners in common make an edge of both.
bool triangles_apart(const VertexId* a, const VertexId* b, const EmbeddedStars& stars) {
  VertexId corner = -1;
  int shared = 0;
  for (int k = 0; k < 3; ++k)
    if (a[k] >= 0 && (a[k] == b[0] || a[k] == b[1] || a[k] == b[2])) {
      corner = a[k];
      ++shared;
    }
  return shared >= 2 || (shared == 1 && stars.at(corner));
}

}  // namespace

bool neighbours_apart(const Facet& A, const Facet& B, const EmbeddedStars& stars) {
  if (A.id.size() == 3 && B.id.size() == 3) return triangles_apart(A.id.data(), B.id.data(), stars);
  if (share_an_edge(A, B)) return true;
  VertexId corner = -1;
  int shared = 0;
  for (const VertexId p : A.id)
    if (B.has_vertex(p)) {
      corner = p;
      ++shared;
    }
  return shared == 1 && stars.at(corner);
}

namespace {

// Where each facet is listed, for the search of pairs: the cells of its box,
// whether it is listed in every one of them (not hidden behind a blocker in
// any), and for a facet that is not, in which: a bit per cell of its box, or
// where its box holds more than kDenseCells cells (a facet beside the near
// plane in perspective spans the screen, and is listed in few of its box's
// cells: a sphere of 10^6 triangles seen from inside took 14 GB of such
// bits), the list of those cells.
struct Listing {
  static constexpr long kDenseCells = 1 << 10;
  const CellRange* range = nullptr;   // per facet (Grid::facet_range)
  int columns = 0;                    // the grid's (cell (x, y) is y * columns + x)
  std::vector<char> complete;
  std::vector<std::size_t> first;   // an incomplete facet's bits: rows of `words` words from bits[first]
  std::vector<int> words;           // (0 for a facet whose cells are listed instead)
  std::vector<std::uint64_t> bits;
  std::vector<std::size_t> cells_first;   // a listed facet's cells: cells[cells_first[f] .. cells_first[f + 1]),
  std::vector<std::uint32_t> cells;       // ascending

  bool listed_by_cell(int f) const { return !complete[f] && words[f] == 0; }
  std::size_t count(int f) const { return cells_first[f + 1] - cells_first[f]; }

  // Whether facet f is listed in cell (x, y) of its box.
  bool listed(int f, int x, int y) const {
    if (complete[f]) return true;
    if (listed_by_cell(f)) {
      const auto from = cells.begin() + static_cast<std::ptrdiff_t>(cells_first[f]);
      const auto to = cells.begin() + static_cast<std::ptrdiff_t>(cells_first[f + 1]);
      return std::binary_search(from, to, static_cast<std::uint32_t>(y * columns + x));
    }
    return (listed64(f, x, y) & 1) != 0;
  }

  // Where facet f (not listed by cell) is listed among the 64 cells of row y
  // from column x on (bit k: column x + k; x within f's box). Beyond the box's
  // last column: zeros, or ones for a complete facet (the caller masks them).
  std::uint64_t listed64(int f, int x, int y) const {
    if (complete[f]) return ~std::uint64_t(0);
    const CellRange& r = range[f];
    const int col = x - r.x0, w = col / 64, off = col % 64, n = words[f];
    const std::uint64_t* row = bits.data() + first[f] + static_cast<std::size_t>(y - r.y0) * static_cast<std::size_t>(n);
    std::uint64_t v = row[w] >> off;
    if (off && w + 1 < n) v |= row[w + 1] << (64 - off);
    return v;
  }
};

Listing listing_of(const Grid& g, const ScreenScene& ss, int threads) {
  const int nf = static_cast<int>(ss.facet_count());
  Listing l;
  l.range = g.facet_range.data();
  l.columns = g.X.cells();
  std::vector<int> listed(ss.facet_count(), 0);
  for (const Cell& cell : g.cells) {
    for (int fi : cell.facets) ++listed[fi];
    if (cell.blocker >= 0) ++listed[cell.blocker];
  }
  l.complete.resize(ss.facet_count());
  l.first.assign(ss.facet_count(), 0);
  l.words.assign(ss.facet_count(), 0);
  l.cells_first.assign(ss.facet_count() + 1, 0);
  std::size_t nbits = 0;
  for (int fi = 0; fi < nf; ++fi) {
    const CellRange& r = l.range[fi];
    const long box_cells = static_cast<long>(r.x1 - r.x0 + 1) * (r.y1 - r.y0 + 1);
    l.complete[fi] = listed[fi] == box_cells;
    l.cells_first[fi + 1] = l.cells_first[fi];
    if (l.complete[fi]) continue;
    if (box_cells > Listing::kDenseCells) {
      l.cells_first[fi + 1] += static_cast<std::size_t>(listed[fi]);
      continue;
    }
    l.first[fi] = nbits;
    l.words[fi] = (r.x1 - r.x0 + 64) / 64;
    nbits += static_cast<std::size_t>(l.words[fi]) * static_cast<std::size_t>(r.y1 - r.y0 + 1);
  }
  // The cells of the facets listed by cell, in row order (ascending).
  l.cells.resize(l.cells_first[ss.facet_count()]);
  std::vector<std::size_t> fill(l.cells_first.begin(), l.cells_first.end() - 1);
  for (std::size_t c = 0; c < g.cells.size(); ++c) {
    auto add = [&](int fi) {
      if (l.listed_by_cell(fi)) l.cells[fill[static_cast<std::size_t>(fi)]++] = static_cast<std::uint32_t>(c);
    };
    for (int fi : g.cells[c].facets) add(fi);
    if (g.cells[c].blocker >= 0) add(g.cells[c].blocker);
  }
  // The bits, rows of cells in parallel (a row of cells sets only its own row of
  // each facet's bits).
  l.bits.assign(nbits, 0);
  parallel_for(g.Y.cells(), threads, [&](int iy) {
    for (int ix = 0; ix < g.X.cells(); ++ix) {
      const Cell& cell = g.at(ix, iy);
      auto mark = [&](int fi) {
        const CellRange& r = l.range[fi];
        if (l.complete[fi] || l.listed_by_cell(fi) || ix < r.x0 || ix > r.x1 || iy < r.y0 || iy > r.y1) return;
        const int col = ix - r.x0;
        l.bits[l.first[fi] + static_cast<std::size_t>(iy - r.y0) * static_cast<std::size_t>(l.words[fi]) +
               static_cast<std::size_t>(col / 64)] |= std::uint64_t(1) << (col % 64);
      };
      for (int fi : cell.facets) mark(fi);
      if (cell.blocker >= 0) mark(cell.blocker);
    }
  });
  return l;
}

// Whether cell (ix, iy), which lists facets a and b, is the first in row order
// to list both: each pair is tested once, there. Where both are listed in every
// cell of their boxes, that is the first cell the boxes share; where one is
// listed by cell, its cells before (ix, iy) in the common box are looked at;
// else the common box's cells before (ix, iy), 64 at a time.
bool first_common_cell(const Listing& l, int a, int b, int ix, int iy) {
  const CellRange &ra = l.range[a], &rb = l.range[b];
  const int x0 = std::max(ra.x0, rb.x0), x1 = std::min(ra.x1, rb.x1), y0 = std::max(ra.y0, rb.y0);
  if (l.complete[a] && l.complete[b]) return ix == x0 && iy == y0;
  if (l.listed_by_cell(a) || l.listed_by_cell(b)) {
    // Row by row, the listed one's cells within the common box (the one with
    // fewer cells, when both are).
    const bool by_a = l.listed_by_cell(a) && (!l.listed_by_cell(b) || l.count(a) <= l.count(b));
    const int s = by_a ? a : b, o = by_a ? b : a;
    const std::uint32_t* first = l.cells.data() + l.cells_first[s];
    const std::uint32_t* last = l.cells.data() + l.cells_first[s + 1];
    for (int y = y0; y <= iy; ++y) {
      const int end = y < iy ? x1 : ix - 1;   // (in row iy: the columns before ix)
      const auto row = static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(l.columns);
      for (const std::uint32_t* c = std::lower_bound(first, last, row + static_cast<std::uint32_t>(x0));
           c != last && *c <= row + static_cast<std::uint32_t>(end) && end >= x0; ++c)
        if (l.listed(o, static_cast<int>(*c - row), y)) return false;
    }
    return true;
  }
  for (int y = y0; y <= iy; ++y) {
    const int end = y < iy ? x1 : ix - 1;   // (in row iy: the columns before ix)
    for (int x = x0; x <= end; x += 64) {
      std::uint64_t both = l.listed64(a, x, y) & l.listed64(b, x, y);
      if (end - x < 63) both &= (std::uint64_t(1) << (end - x + 1)) - 1;
      if (both) return false;
    }
  }
  return true;
}

// A facet as the pair search reads it, copied next to the others of its cell;
// a triangle's corners too (most pairs on a mesh are told apart by them, and
// the facets themselves are then never read).
struct Member {
  int fi, face;
  int solid;                        // ScreenScene::solid, or -1
  CGAL::Bbox_2 box;
  double zlo, zhi;
  std::array<VertexId, 3> corner;   // a triangle's, else corner[0] = kNotTriangle
  static constexpr VertexId kNotTriangle = -2;
};

struct Crossing {   // facets fa < fb cross along p-q
  int fa, fb;
  P2 p, q;
};

// The crossings of the pairs of facets that cell (ix, iy) is the first to list
// together, appended to `out`.
void crossings_in_cell(const Grid& g, const ScreenScene& ss, const Listing& l, const EmbeddedStars& stars, int ix,
                       int iy, std::vector<Member>& members, std::vector<Crossing>& out, std::int64_t& tested) {
  const Cell& cell = g.at(ix, iy);
  members.clear();
  auto add = [&](int fi) {
    const Facet& f = ss.facet(fi);
    Member m{fi, f.face, solid_of(ss, fi), f.box, f.zlo, f.zhi, {Member::kNotTriangle, -1, -1}};
    if (f.id.size() == 3) std::copy(f.id.begin(), f.id.end(), m.corner.begin());
    members.push_back(m);
  };
  for (int fi : cell.facets) add(fi);
  if (cell.blocker >= 0) add(cell.blocker);
  // In order of their nearest depth, each facet meets only those after it that
  // begin before it ends: pairs whose depth ranges are apart (no point of one at
  // the other's depth) are never looked at. (A mesh seen obliquely: most of a
  // cell's facets lie at other depths; the order of the tests changes nothing found.)
  std::sort(members.begin(), members.end(), [](const Member& m, const Member& n) { return m.zlo < n.zlo; });
  for (std::size_t i = 0; i < members.size(); ++i)
    for (std::size_t j = i + 1; j < members.size() && members[j].zlo <= members[i].zhi; ++j) {
      const Member &m = members[i], &n = members[j];
      if (m.fi == n.fi || m.face == n.face || (m.solid >= 0 && m.solid == n.solid) || !CGAL::do_overlap(m.box, n.box))
        continue;
      const bool triangles = m.corner[0] != Member::kNotTriangle && n.corner[0] != Member::kNotTriangle;
      if (triangles && triangles_apart(m.corner.data(), n.corner.data(), stars)) continue;
      const int fa = std::min(m.fi, n.fi), fb = std::max(m.fi, n.fi);
      if (!first_common_cell(l, fa, fb, ix, iy)) continue;
      const Facet &A = ss.facet(fa), &B = ss.facet(fb);
      if (!triangles && neighbours_apart(A, B, stars)) continue;
      ++tested;
      P2 p, q;
      if (intersection_segment(A, B, ss.world, p, q)) out.push_back(Crossing{fa, fb, p, q});
    }
}

}  // namespace

// Faces that pierce each other: an intersection line for every pair of facets of
// different faces that some cell lists together and that cross inside both
// projections (never two of one solid that does not meet itself). Rows of cells
// in parallel, each pair tested in the first cell that lists both; the lines
// are appended in the order of their pairs.
void add_intersection_lines(const Grid& g, ScreenScene& ss, int threads, Stats& stats) {
  if (occluders_in_one_solid(ss)) {   // (no pair to test)
    stats.count("embedded_stars", 0);
    stats.count("facet_pairs_tested", 0);
    stats.count("intersection_lines", 0);
    return;
  }
  const Listing l = listing_of(g, ss, threads);
  const EmbeddedStars stars(ss, threads, !occluders_all_in_solids(ss));
  std::vector<std::vector<Crossing>> by_row(static_cast<std::size_t>(g.Y.cells()));
  std::vector<std::int64_t> tested_by_row(by_row.size(), 0);
  parallel_for(g.Y.cells(), threads, [&](int iy) {
    std::vector<Member> members;
    std::vector<Crossing> found;   // (filled here, stored once: rows side by side share cache lines)
    std::int64_t tested = 0;
    for (int ix = 0; ix < g.X.cells(); ++ix) crossings_in_cell(g, ss, l, stars, ix, iy, members, found, tested);
    by_row[static_cast<std::size_t>(iy)] = std::move(found);
    tested_by_row[static_cast<std::size_t>(iy)] = tested;
  });
  std::vector<Crossing> found;
  std::int64_t tested = 0;
  for (std::size_t row = 0; row < by_row.size(); ++row) {
    tested += tested_by_row[row];
    std::move(by_row[row].begin(), by_row[row].end(), std::back_inserter(found));
  }
  std::sort(found.begin(), found.end(), [](const Crossing& x, const Crossing& y) {
    return std::pair(x.fa, x.fb) < std::pair(y.fa, y.fb);
  });
  std::deque<P3>& line_ends = ss.ends.emplace_back();
  for (const Crossing& c : found) {
    ss.curves.push_back(crossing_curve(ss.facet(c.fa), ss.facet(c.fb), c.fa, c.fb, c.p, c.q, line_ends));
  }
  stats.count("embedded_stars", stars.count());
  stats.count("facet_pairs_tested", tested);
  stats.count("intersection_lines", static_cast<std::int64_t>(found.size()));
}

namespace {

// Step 7 for the curves `take` admits, into the cells `into` admits: each goes
// to the cells it passes through, unless it lies wholly behind the cell's
// blocker (7a-i). Returns how many it listed nowhere (hidden: 7b). Rows of
// cells in parallel (`into` must not depend on what this call lists).
template <class Take, class Into>
std::int64_t bucket(Grid& g, const ScreenScene& ss, int threads, Take&& take, Into&& into, std::int64_t& listed) {
  const int nc = static_cast<int>(ss.curves.size());
  // Each curve's cells, once (a long curve is met again in every row it crosses).
  std::vector<CellRange> range(ss.curves.size());
  const ItemsByRow rows = items_by_row(g, nc, threads, [&](int ci) {
    if (!take(ci)) return kNoRows;
    const CellRange& r = range[static_cast<std::size_t>(ci)] = range_of(g, ss.curves[ci].box);
    return std::array<int, 2>{r.y0, r.y1};
  });
  std::vector<std::vector<int>> kept_by_row(rows.size());
  std::vector<std::int64_t> listed_by_row(rows.size(), 0);
  parallel_for(g.Y.cells(), threads, [&](int iy) {
    UpwardRounding upward;   // meets_cell, curve_behind: our own filtered predicates
    const auto row = static_cast<std::size_t>(iy);
    std::vector<int> kept_here;   // (filled here, stored once: rows side by side share cache lines)
    std::int64_t listed_here = 0;
    for (int ci : rows[row]) {
      const Curve& cv = ss.curves[ci];
      const CellRange& r = range[static_cast<std::size_t>(ci)];
      bool kept = false;
      // (A cell the double box reaches only by rounding may be kept: harmless,
      // cut points count only in the cell that holds them.)
      const bool one_cell = r.x0 == r.x1 && r.y0 == r.y1;
      const std::optional<RowCorners> line =
          one_cell ? std::nullopt : std::optional<RowCorners>(std::in_place, *cv.s, *cv.t, g, r.x0, r.x1, iy);
      for (int ix = r.x0; ix <= r.x1; ++ix) {
        if (!into(ix, iy)) continue;
        Cell& cell = g.at(ix, iy);
        if (line && !line->meets(ix)) continue;
        if (cell.blocker >= 0 && curve_behind(cv, ss.facet(cell.blocker), ss.world)) continue;
        cell.curves.push_back(ci);
        kept = true;
        ++listed_here;
      }
      if (kept) kept_here.push_back(ci);
    }
    kept_by_row[row] = std::move(kept_here);
    listed_by_row[row] = listed_here;
  });
  std::vector<char> kept(ss.curves.size(), 0);
  mark_kept(kept_by_row, kept);
  std::int64_t hidden = 0;
  for (int ci = 0; ci < nc; ++ci) hidden += take(ci) && !kept[static_cast<std::size_t>(ci)];
  for (std::int64_t l : listed_by_row) listed += l;
  return hidden;
}

// For the drawn lines alone, after the first cutting pass: bucket_curves listed
// the curves that are not drawn only where a drawn one is (hot cells). Those now
// needed go to their other cells too, and every curve that is not drawn to those
// cells, for the second pass.
void bucket_needed_curves(Grid& g, const ScreenScene& ss, const std::vector<char>& needed, int threads) {
  std::vector<char> hot(g.cells.size());
  for (std::size_t k = 0; k < g.cells.size(); ++k) hot[k] = !g.cells[k].curves.empty();
  auto cold = [&](int ix, int iy) { return !hot[static_cast<std::size_t>(iy) * g.X.cells() + ix]; };
  std::int64_t listed = 0;
  bucket(g, ss, threads, [&](int ci) { return !ss.curves[ci].drawn && needed[ci]; }, cold, listed);
  bucket(g, ss, threads, [&](int ci) { return !ss.curves[ci].drawn && !needed[ci]; },
         [&](int ix, int iy) { return cold(ix, iy) && !g.at(ix, iy).curves.empty(); }, listed);
}

}  // namespace

namespace {

// Per latent curve: whether its box reaches a cell that holds a drawn curve (the
// cells the undrawn ones are listed in for a lines-only drawing).
std::vector<char> latent_near_drawn(const Grid& g, const ScreenScene& ss, int threads) {
  std::vector<char> wanted(ss.latent_piece.size(), 0);
  parallel_chunks(static_cast<int>(wanted.size()), 4096, threads, [&](int, Chunk c) {
    for (int i = c.begin; i < c.end; ++i) {
      if (!g.latent_near.empty() && !g.latent_near[static_cast<std::size_t>(i)]) continue;   // (nowhere near)
      const CellRange r = range_of(g, latent_box(ss, static_cast<std::size_t>(i)));
      for (int iy = r.y0; iy <= r.y1 && !wanted[i]; ++iy)
        for (int ix = r.x0; ix <= r.x1 && !wanted[i]; ++ix) wanted[i] = !g.at(ix, iy).curves.empty();
    }
  });
  return wanted;
}

}  // namespace

// Step 7: each curve goes to the cells it passes through, unless it lies wholly
// behind the cell's blocker (7a-i); a curve listed nowhere is hidden (7b). For
// the drawn lines alone: the drawn curves everywhere, the others only into cells
// where a drawn one is (where they could meet it; cut_curves adds the rest it needs).
void bucket_curves(Grid& g, ScreenScene& ss, bool regions, int threads, Stats& stats) {
  std::int64_t listed = 0, hidden = 0;
  auto everywhere = [](int, int) { return true; };
  if (regions) {
    hidden = bucket(g, ss, threads, [](int) { return true; }, everywhere, listed);
  } else {
    hidden = bucket(g, ss, threads, [&](int ci) { return ss.curves[ci].drawn; }, everywhere, listed);
    auto holds_drawn = [&](int ix, int iy) { return !g.at(ix, iy).curves.empty(); };
    // The latent curves (not drawn) those cells may list: made now.
    const std::vector<char> wanted = latent_near_drawn(g, ss, threads);
    stats.count("curves_made_late", std::count(wanted.begin(), wanted.end(), 1));
    make_latent_curves(ss, wanted, threads);
    bucket(g, ss, threads, [&](int ci) { return !ss.curves[ci].drawn; }, holds_drawn, listed);
  }
  stats.count("curve_cells", listed);
  stats.count("edges_culled_behind_blocking_face", hidden);
}

// Along x: depth_C(p) = N_C / d_C with d_C = t.x - s.x and
// N_C = s.z d_C + (p.x - s.x)(t.z - s.z); the sign of N_C d_D - N_D d_C times
// those of d_C and d_D. A filtered predicate: no lazy number is built.
CGAL::Sign depth_gap(const Curve& C, const Curve& D, const P2& p, bool along_x) {
  auto u = [&](const P3& q) -> const FT& { return along_x ? q.x : q.y; };
  const CGAL::Sign dc = CGAL::compare(u(*C.t), u(*C.s)), dd = CGAL::compare(u(*D.t), u(*D.s));
  const CGAL::Sign cross = filtered_sign(
      [&] {
        const Interval pu = along_x ? approx_x(p) : approx_y(p);
        auto n = [&](const Curve& K, Interval& d) {
          d = approx_of(u(*K.t)) - approx_of(u(*K.s));
          return approx_of(K.s->z) * d + (pu - approx_of(u(*K.s))) * (approx_of(K.t->z) - approx_of(K.s->z));
        };
        Interval d_c, d_d;
        const Interval n_c = n(C, d_c), n_d = n(D, d_d);
        return n_c * d_d - n_d * d_c;
      },
      [&]() -> mpq_class {
        const mpq_class pu = along_x ? exact_x(p) : exact_y(p);
        auto n = [&](const Curve& K, mpq_class& d) -> mpq_class {
          d = to_mpq(u(*K.t)) - to_mpq(u(*K.s));
          return to_mpq(K.s->z) * d + (pu - to_mpq(u(*K.s))) * (to_mpq(K.t->z) - to_mpq(K.s->z));
        };
        mpq_class d_c, d_d;
        const mpq_class n_c = n(C, d_c), n_d = n(D, d_d);
        return n_c * d_d - n_d * d_c;
      });
  return cross * dc * dd;
}

bool depth_crossing(const Curve& C, const Curve& D, const P2& lo, const P2& hi, P2& x) {
  // The signs first, on filtered predicates; the point (lazy) only for a crossing.
  const bool along_x = CGAL::compare_x(C.s->xy(), C.t->xy()) != CGAL::EQUAL;
  if (depth_gap(C, D, lo, along_x) * depth_gap(C, D, hi, along_x) >= 0) return false;
  FT flo = depth_on(C, lo) - depth_on(D, lo), fhi = depth_on(C, hi) - depth_on(D, hi);
  FT mu = flo / (flo - fhi);
  x = frozen(lo + mu * (hi - lo));   // (cut into both curves: shared by the threads)
  return true;
}

P2 plane_crossing(const Curve& C, const Facet& F) {
  const FT ds = C.s->z - F.depth_at(C.s->xy()), dt = C.t->z - F.depth_at(C.t->xy());
  return frozen(C.s->xy() + (ds / (ds - dt)) * (C.t->xy() - C.s->xy()));
}

namespace {

// Where segments [a, b] and [c, d] cross (they do, properly). In exact builds a
// lazy point of one node: its interval is computed here, and its exact value
// (directly in GMP, the same formula) only if a predicate or the output needs it.
// Most crossings are hidden and never do. The interval is the intersection of
// the two segments' parameterisations: a crossing on an axis-parallel segment
// gets that segment's exact coordinate, so points along it compare cheaply.
template <class Kernel>
struct CrossingOf {
  typedef typename Kernel::Point_2 result_type;
  using N = typename Kernel::FT;   // (not auto: GMP's expression templates)
  result_type operator()(const result_type& a, const result_type& b, const result_type& c,
                         const result_type& d) const {
    if constexpr (std::is_same_v<N, mpq_class>) return fraction_free(a, b, c, d);
    const N ux = b.x() - a.x(), uy = b.y() - a.y();
    const N vx = d.x() - c.x(), vy = d.y() - c.y();
    const N wx = c.x() - a.x(), wy = c.y() - a.y();
    const N den = ux * vy - uy * vx;
    const N lambda = (wx * vy - wy * vx) / den;
    if constexpr (std::is_same_v<N, Interval>) {
      if (den.inf() <= 0 && den.sup() >= 0) return result_type(Interval::largest(), Interval::largest());
      const N mu = (wx * uy - wy * ux) / den;
      return result_type(meet(a.x() + lambda * ux, c.x() + mu * vx), meet(a.y() + lambda * uy, c.y() + mu * vy));
    } else {
      return result_type(N(a.x() + lambda * ux), N(a.y() + lambda * uy));
    }
  }
  // The exact value on integers: the eight coordinates over one common
  // denominator L (projected doubles share a power of two), the formula on their
  // numerators, one normalisation per coordinate at the end, instead of a
  // normalised rational (gcd) at every step. (Other denominators: homogeneous.)
  static result_type fraction_free(const result_type& a, const result_type& b, const result_type& c,
                                   const result_type& d) {
    // A segment parallel to each axis (a vertical edge crossing a horizontal
    // one, as a view along an axis sees parts aligned with the axes, in
    // perspective too): their own coordinates, with no arithmetic.
    // (Either coordinate alone: kept below, where the other is computed.)
    const std::array<const mpq_class*, 2> own{c.x() == d.x() ? &c.x() : a.x() == b.x() ? &a.x() : nullptr,
                                              c.y() == d.y() ? &c.y() : a.y() == b.y() ? &a.y() : nullptr};
    if (own[0] && own[1]) return result_type(*own[0], *own[1]);
    const mpq_class* q[8] = {&a.x(), &a.y(), &b.x(), &b.y(), &c.x(), &c.y(), &d.x(), &d.y()};
    DyadicScratch& z = dyadic_scratch();
    mp_bitcnt_t E = 0;
    if (!over_power_of_two(q, E, z.X)) return homogeneous(a, b, c, d, own);
    mpz_sub(z.ux, z.X[2], z.X[0]), mpz_sub(z.uy, z.X[3], z.X[1]);
    mpz_sub(z.vx, z.X[6], z.X[4]), mpz_sub(z.vy, z.X[7], z.X[5]);
    mpz_sub(z.wx, z.X[4], z.X[0]), mpz_sub(z.wy, z.X[5], z.X[1]);
    mpz_mul(z.den, z.ux, z.vy), mpz_submul(z.den, z.uy, z.vx);
    mpz_mul(z.num, z.wx, z.vy), mpz_submul(z.num, z.wy, z.vx);
    // On a segment parallel to an axis (a vertical edge seen with the up axis
    // upright: common), that coordinate is the segment's own, already canonical
    // (no product, no gcd).
    auto coordinate = [&](int k, const mpz_t x0, const mpz_t u) {
      if (own[static_cast<std::size_t>(k)]) return *own[static_cast<std::size_t>(k)];
      mpz_mul(z.n, x0, z.den), mpz_addmul(z.n, z.num, u);   // x = n / (den 2^E)
      mpq_class r;   // (0 / 1)
      if (mpz_sgn(z.n) != 0) {
        // Lowest terms: n and den share g; what is left of n shares with 2^E
        // only powers of two, and only where den / g is odd.
        mpz_gcd(z.g, z.n, z.den);
        mpz_divexact(mpq_numref(r.get_mpq_t()), z.n, z.g);
        mpz_divexact(mpq_denref(r.get_mpq_t()), z.den, z.g);
        const mp_bitcnt_t twos = std::min<mp_bitcnt_t>(E, mpz_scan1(mpq_numref(r.get_mpq_t()), 0));
        mpz_tdiv_q_2exp(mpq_numref(r.get_mpq_t()), mpq_numref(r.get_mpq_t()), twos);
        mpz_mul_2exp(mpq_denref(r.get_mpq_t()), mpq_denref(r.get_mpq_t()), E - twos);
        if (mpz_sgn(mpq_denref(r.get_mpq_t())) < 0) {
          mpz_neg(mpq_numref(r.get_mpq_t()), mpq_numref(r.get_mpq_t()));
          mpz_neg(mpq_denref(r.get_mpq_t()), mpq_denref(r.get_mpq_t()));
        }
      }
      return r;
    };
    return result_type(coordinate(0, z.X[0], z.ux), coordinate(1, z.X[1], z.uy));
  }
  // The integers fraction_free works on, per thread: allocated once, grown as
  // needed. (Made and freed for each crossing, ~25 of them were a fifth of a
  // crossing's exact value on random squares seen obliquely.)
  struct DyadicScratch {
    mpz_t X[8], ux, uy, vx, vy, wx, wy, den, num, n, g;
    DyadicScratch() {
      for (mpz_t& x : X) mpz_init2(x, 256);
      for (mpz_ptr x : {ux, uy, vx, vy, wx, wy, den, num, n, g}) mpz_init2(x, 512);
    }
    ~DyadicScratch() {
      for (mpz_t& x : X) mpz_clear(x);
      for (mpz_ptr x : {ux, uy, vx, vy, wx, wy, den, num, n, g}) mpz_clear(x);
    }
    DyadicScratch(const DyadicScratch&) = delete;
    DyadicScratch& operator=(const DyadicScratch&) = delete;
  };
  static DyadicScratch& dyadic_scratch() {
    thread_local DyadicScratch scratch;
    return scratch;
  }
  // The crossing in homogeneous coordinates, where the denominators are not
  // all powers of two (a perspective view's images, N / W, over odd parts of
  // their W): each point (x, y) = (nx / dx, ny / dy) as (nx dy, ny dx, dx dy)
  // (or (nx, ny, d) where dx = dy = d: mostly), the line through two points
  // their cross product, the crossing the two lines' cross product (X, Y, W),
  // and x = X / W, y = Y / W normalised: one gcd per coordinate, where a
  // common denominator of the eight took an lcm of the four W's first (three
  // gcds of products) and a division per coordinate. (A coordinate that both
  // ends of one segment share, own[k], is that segment's, as above.)
  static result_type homogeneous(const result_type& a, const result_type& b, const result_type& c,
                                 const result_type& d, const std::array<const mpq_class*, 2>& own) {
    struct H {
      mpz_class x, y, w;
    };
    auto lift = [](const result_type& p) {
      const mpq_class &x = p.x(), &y = p.y();
      if (x.get_den() == y.get_den()) return H{x.get_num(), y.get_num(), x.get_den()};
      return H{x.get_num() * y.get_den(), y.get_num() * x.get_den(), x.get_den() * y.get_den()};
    };
    auto cross = [](const H& p, const H& r) {
      return H{p.y * r.w - p.w * r.y, p.w * r.x - p.x * r.w, p.x * r.y - p.y * r.x};
    };
    const H m = cross(cross(lift(a), lift(b)), cross(lift(c), lift(d)));
    auto coordinate = [&](const mpq_class* kept, const mpz_class& n) {
      if (kept) return *kept;
      mpq_class r;
      r.get_num() = n;
      r.get_den() = m.w;
      r.canonicalize();
      return r;
    };
    return result_type(coordinate(own[0], m.x), coordinate(own[1], m.y));
  }
  // Where every denominator is a power of two (an orthographic view's
  // coordinates: sums of products of doubles), their common one is the largest,
  // 2^E, and X[i] = q[i] 2^E shifted: no gcd (mpz_lcm takes one), no division.
  static bool over_power_of_two(const mpq_class* const (&q)[8], mp_bitcnt_t& E, mpz_t (&X)[8]) {
    mp_bitcnt_t e[8];
    E = 0;
    for (int i = 0; i < 8; ++i) {
      const mpz_srcptr den = q[i]->get_den_mpz_t();
      e[i] = mpz_scan1(den, 0);
      if (mpz_sizeinbase(den, 2) != e[i] + 1) return false;   // (another bit set)
      E = std::max(E, e[i]);
    }
    for (int i = 0; i < 8; ++i) mpz_mul_2exp(X[i], q[i]->get_num_mpz_t(), E - e[i]);
    return true;
  }
  // Two enclosures of one number: their common part.
  static Interval meet(const Interval& p, const Interval& q) {
    return Interval(std::max(p.inf(), q.inf()), std::min(p.sup(), q.sup()));
  }
};


}  // namespace

P2 crossing_point(const P2& a, const P2& b, const P2& c, const P2& d) {
#ifdef VISMAP_FLOAT_KERNEL
  return CrossingOf<K>()(a, b, c, d);
#else
  steady_detail::ApproxPoint approx;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    approx = CrossingOf<K::Approximate_kernel>()(a.approx(), b.approx(), c.approx(), d.approx());
  }
  // (Segments nearly parallel: an unbounded interval, which would never narrow,
  // and the assembly buckets points by their intervals. Made exact now, before
  // any thread shares it: rare.)
  if (!steady_detail::bounded(approx)) {
    const auto e = CrossingOf<K::Exact_kernel>::fraction_free(CGAL::exact(a), CGAL::exact(b), CGAL::exact(c),
                                                              CGAL::exact(d));
    return steady_point(FT(e.x()), FT(e.y()));
  }
  // (Its interval kept, as steady_point's: the two curves through it may be
  // cut and classified on different threads.)
  return steady_detail::kept_point(approx, &CrossingOf<K::Exact_kernel>::fraction_free, a, b, c, d);
#endif
}

namespace {

// (Lines only) a drawn curve crossed properly by one that is not drawn, and
// the box of the crossing (its intervals when made).
struct DrawnCrossed {
  int drawn, other;
  CGAL::Bbox_2 box;
};

// What cutting one row of cells finds, in the order the cells and pairs were
// looked at: the rows are cut in parallel and joined in row order.
struct RowCuts {
  std::vector<std::pair<int, P2>> at;          // (curve, cut point)
  std::vector<std::pair<int, int>> overlaps;   // collinear curves sharing more than a point
  std::vector<int> met;                        // (lines only) curves found to meet a drawn one
  std::vector<DrawnCrossed> crossed;           // (lines only) crossings of a drawn curve, in this row's cells
  std::int64_t pairs = 0, crossings = 0, uncut = 0, behind = 0;
};

// How two curves meet (Cutter::meet): not at all (or crossing apart), only at
// an end point they share and not along a common line (no cut), crossing
// properly (inside both: Cutter::crossing is the point), or more (an end on
// the other's inside, an overlap).
enum class Contact { kNone, kSharedEnd, kCrossing, kMore };

struct Cutter {
  const Grid& g;
  const ScreenScene& ss;
  RowCuts& row;
  int ix, iy;
  // The last proper crossing meet() found, where this cell holds it (else none).
  std::optional<P2> crossing = std::nullopt;
  // Per curve of the cell (its place in Cell::curves): whether hidden_in_cell,
  // -1 until asked. (Asked only of curves that may cross: most pairs are told
  // apart on their boxes and intervals for less than the test costs. Once
  // known hidden, a curve's other pairs in the cell are not looked at.)
  const Cell* cell = nullptr;
  std::vector<signed char> hidden{};

  void start_cell(const Cell& c) {
    cell = &c;
    hidden.assign(c.curves.size(), -1);
  }
  bool known_hidden(std::size_t i) const { return hidden[i] > 0; }
  bool hidden_here(std::size_t i) {
    if (hidden[i] < 0) {
      hidden[i] = hidden_in_cell(ss.curves[cell->curves[i]], *cell, corners(g, ix, iy), ss);
      row.behind += hidden[i];
    }
    return hidden[i] != 0;
  }

  void cut(int c, const P2& p) {
    if (in_cell(g, ix, iy, p)) row.at.emplace_back(c, p);
  }
  // p strictly between the end points of C (p known to be on C's line). (An end
  // point itself is not: known without a predicate, which on equal coordinates
  // cannot be settled by its filter.)
  static bool strictly_within(const Curve& C, const P2& p) {
    if (same_rep(p, C.s->xy()) || same_rep(p, C.t->xy())) return false;
    return between_on_line(C.s->xy(), p, C.t->xy(), /*strictly=*/true);
  }

  // Cuts C and D, the cell's curves i and j, whose boxes meet, where they
  // cross or touch (but where they cross apart: see meet(), or where either is
  // hidden throughout the cell: hidden_in_cell); how they may meet (closed
  // segments), kNone where they surely do not, cross apart, or either is
  // hidden throughout the cell (then nothing they share there is seen, not
  // even an end: no vertex of the map, no line joined there). The caller holds
  // an UpwardRounding (one switch per cell, not per pair): the points'
  // intervals first, CGAL's predicates (rounding to nearest) only where those
  // cannot tell. (Where the intervals tell, meet() would cut nothing, and would
  // say they meet exactly where they share an end.)
  Contact meet_on_intervals_first(std::size_t i, std::size_t j, bool apart) {
    const int ci = cell->curves[i], di = cell->curves[j];
    bool shared_end = false;
    if (no_cut_on_intervals(ci, di, apart, shared_end)) return shared_end ? Contact::kSharedEnd : Contact::kNone;
    if (hidden_here(i) || hidden_here(j)) return Contact::kNone;
    NearestRounding nearest;
    return meet(ci, di, apart);
  }
  bool boxes_meet(int ci, int di) {
    if (!CGAL::do_overlap(ss.curves[ci].box, ss.curves[di].box)) return false;
    ++row.pairs;
    return true;
  }

  // A common end point of C and D known without a predicate: the same vertex,
  // or one point (a near-plane cut, made once for all the curves through it).
  // Where there is one, C = [p, a] and D = [p, b].
  struct CommonEnd {
    const P2 *p, *a, *b;
    VertexId ip, ia, ib;   // their vertex ids (Curve::vs)
  };
  static std::optional<CommonEnd> common_end(const Curve& C, const Curve& D) {
    const P2 &cs = C.s->xy(), &ct = C.t->xy(), &ds = D.s->xy(), &dt = D.t->xy();   // (references: no handle copied)
    auto same = [](long a, long b, const P2& p, const P2& q) { return a >= 0 ? a == b : b < 0 && same_rep(p, q); };
    const bool ss_ = same(C.vs, D.vs, cs, ds), st = same(C.vs, D.vt, cs, dt), ts = same(C.vt, D.vs, ct, ds),
               tt = same(C.vt, D.vt, ct, dt);
    if (!(ss_ || st || ts || tt)) return std::nullopt;
    const bool ps = ss_ || st, pd = ss_ || ts;
    return CommonEnd{ps ? &cs : &ct, ps ? &ct : &cs, pd ? &dt : &ds,
                     ps ? C.vs : C.vt, ps ? C.vt : C.vs, pd ? D.vt : D.vs};
  }

  // CGAL::orientation(p, q, r) of points that may be vertex images (ids, or
  // -1): on the intervals, then three images on one screen line x = c or y = c
  // (ExactSource::same_screen_coordinate), then, for three images in an
  // orthographic view, from the world (ExactSource::screen_cross_sign), else
  // exactly, fraction-free. Counted as CGAL's.
  CGAL::Orientation orient(const P2& p, VertexId ip, const P2& q, VertexId iq, const P2& r, VertexId ir) const {
#ifdef VISMAP_FLOAT_KERNEL
    (void)ip, (void)iq, (void)ir;
    return CGAL::orientation(p, q, r);
#else
    return filtered_sign(
        [&] {
          return (approx_x(q) - approx_x(p)) * (approx_y(r) - approx_y(p)) -
                 (approx_y(q) - approx_y(p)) * (approx_x(r) - approx_x(p));
        },
        [&]() -> mpq_class {
          auto same = [&](VertexId a, VertexId b, int row) {
            return a >= 0 && b >= 0 &&
                   ss.exact->same_screen_coordinate(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b), row);
          };
          for (int row : {0, 1})
            if (same(ip, iq, row) && same(ip, ir, row)) return 0;
          // Three images seen orthographically: the world decides (binary floats).
          if (!ss.exact->perspective && ip >= 0 && iq >= 0 && ir >= 0) {
            const auto a = static_cast<std::uint32_t>(ip);
            return ss.exact->screen_cross_sign(a, static_cast<std::uint32_t>(iq), a, static_cast<std::uint32_t>(ir));
          }
          return orient_sign(exact_x(p), exact_y(p), exact_x(q), exact_y(q), exact_x(r), exact_y(r));
        });
#endif
  }

  // Whether the intervals of the points tell that C and D (boxes meeting) need
  // no cut, as meet() would find: not collinear at a common end, or apart from
  // each other's lines, or crossing apart() (rounding upward: the caller's
  // UpwardRounding; no CGAL predicate). Else meet() decides. `shared_end`: whether
  // they have a common end (common_end(); asked here once per pair).
  bool no_cut_on_intervals(int ci, int di, bool apart, bool& shared_end) {
    const Curve &C = ss.curves[ci], &D = ss.curves[di];
    auto side = [](const P2& u, const P2& v, const P2& w) {   // (0: not told)
      ++filter_counts.calls;
      const Interval o = (approx_x(v) - approx_x(u)) * (approx_y(w) - approx_y(u)) -
                         (approx_y(v) - approx_y(u)) * (approx_x(w) - approx_x(u));
      return o.inf() > 0 ? 1 : o.sup() < 0 ? -1 : 0;
    };
    if (const auto e = common_end(C, D)) {
      shared_end = true;
      return side(*e->p, *e->a, *e->b) != 0;
    }
    const P2 &cs = C.s->xy(), &ct = C.t->xy(), &ds = D.s->xy(), &dt = D.t->xy();
    const int o1 = side(cs, ct, ds), o2 = side(cs, ct, dt);
    if (o1 != 0 && o1 == o2) return true;
    if (apart && o1 != 0 && o2 != 0) {
      ++row.uncut;
      return true;
    }
    const int o3 = side(ds, dt, cs), o4 = side(ds, dt, ct);
    return o3 != 0 && o3 == o4;
  }

  // The exact side of meet_on_intervals_first(). Curves `apart` (apart()) are cut
  // only where they overlap or one ends on the other: a proper crossing (or
  // none) is no cut, and changes nothing of either (kNone).
  Contact meet(int ci, int di, bool apart) {
    const Curve &C = ss.curves[ci], &D = ss.curves[di];
    const P2 &cs = C.s->xy(), &ct = C.t->xy(), &ds = D.s->xy(), &dt = D.t->xy();   // (references: no handle copied)
    if (const auto e = common_end(C, D)) {
      // C = [p, a], D = [p, b]: they meet only at p unless collinear and pointing the
      // same way; then the longer is cut where the shorter ends. Their depths agree
      // at p, so the depth order cannot change inside the common part.
      const P2 &p = *e->p, &a = *e->a, &b = *e->b;
      if (orient(p, e->ip, a, e->ia, b, e->ib) != CGAL::COLLINEAR || !CGAL::is_positive((a - p) * (b - p)))
        return Contact::kSharedEnd;
      row.overlaps.emplace_back(ci, di);
      if (strictly_within(C, b)) cut(ci, b);
      else if (strictly_within(D, a)) cut(di, a);
      return Contact::kMore;
    }
    auto o1 = orient(cs, C.vs, ct, C.vt, ds, D.vs), o2 = orient(cs, C.vs, ct, C.vt, dt, D.vt);
    if (o1 != CGAL::COLLINEAR && o1 == o2) return Contact::kNone;
    if (o1 == CGAL::COLLINEAR && o2 == CGAL::COLLINEAR) { overlap(ci, di); return Contact::kMore; }
    if (apart && o1 != CGAL::COLLINEAR && o2 != CGAL::COLLINEAR) {   // (a proper crossing or none)
      ++row.uncut;
      return Contact::kNone;
    }
    auto o3 = orient(ds, D.vs, dt, D.vt, cs, C.vs), o4 = orient(ds, D.vs, dt, D.vt, ct, C.vt);
    if (o3 != CGAL::COLLINEAR && o3 == o4) return Contact::kNone;
    if (o1 * o2 < 0 && o3 * o4 < 0) {   // proper crossing
      const P2 p = crossing_point(cs, ct, ds, dt);
      ++row.crossings;
      crossing.reset();
      if (in_cell(g, ix, iy, p)) {   // (as cut(): counted in the cell holding it)
        row.at.emplace_back(ci, p);
        row.at.emplace_back(di, p);
        crossing = p;
      }
      return Contact::kCrossing;
    }
    // T-junctions: an end point of one lies inside the other.
    if (o1 == CGAL::COLLINEAR && strictly_within(C, ds)) cut(ci, ds);
    if (o2 == CGAL::COLLINEAR && strictly_within(C, dt)) cut(ci, dt);
    if (o3 == CGAL::COLLINEAR && strictly_within(D, cs)) cut(di, cs);
    if (o4 == CGAL::COLLINEAR && strictly_within(D, ct)) cut(di, ct);
    return Contact::kMore;
  }

  // A curve none of whose facets hides anything (they are all seen edge-on) gets
  // no intersection lines, yet its visibility changes where it pierces a facet's
  // plane inside the facet: cut it there.
  void pierce(int ci, int fi) {
    const Curve& C = ss.curves[ci];
    const Facet& F = ss.facet(fi);
    if (!CGAL::do_overlap(C.box, F.box)) return;
    // The sides first, as filtered predicates (an end point in F's plane, often a
    // corner of it, is told in the world), the depths only for a crossing.
    if (depth_above(*C.s, F, ss.world, C.vs) * depth_above(*C.t, F, ss.world, C.vt) >= 0) return;
    const P2 p = plane_crossing(C, F);
    if (!strictly_inside(F, p)) return;   // on its boundary: that edge's crossing cuts here
    ++row.crossings;
    cut(ci, p);
  }

  // Collinear curves: cut each at the other's end points inside it, and both where
  // their depths cross, so that the first in depth order is constant on each piece.
  void overlap(int ci, int di) {
    const Curve &C = ss.curves[ci], &D = ss.curves[di];
    const P2 &cs = C.s->xy(), &ct = C.t->xy(), &ds = D.s->xy(), &dt = D.t->xy();
    std::array<P2, 4> pts{cs, ct, ds, dt};
    auto before = [](const P2& a, const P2& b) { return compare_xy_exactly(a, b) == CGAL::SMALLER; };
    std::sort(pts.begin(), pts.end(), before);   // lexicographic: along the line
    // Common part: the middle two, if C and D really overlap.
    const P2 &lo = pts[1], &hi = pts[2];
    if (!before(lo, hi)) return;
    auto inside = [](const P2& a, const P2& b, const P2& p) {   // (an end point is: no predicate)
      return same_rep(p, a) || same_rep(p, b) || between_on_line(a, p, b, /*strictly=*/false);
    };
    if (!(inside(cs, ct, lo) && inside(cs, ct, hi) && inside(ds, dt, lo) && inside(ds, dt, hi))) return;
    row.overlaps.emplace_back(ci, di);
    for (const P2& p : {ds, dt}) if (strictly_within(C, p)) cut(ci, p);
    for (const P2& p : {cs, ct}) if (strictly_within(D, p)) cut(di, p);
    P2 x;
    if (depth_crossing(C, D, lo, hi, x)) { cut(ci, x); cut(di, x); ++row.crossings; }
  }
};

}  // namespace

namespace {

// Each curve's depth range, whether it is covered (Curve::covered), and its
// facets' faces; NaNs where more than two facets share it (never apart from
// anything).
struct DepthSpan {
  double lo, hi;
  std::array<int, 2> face;   // (-1: none)
  bool covered;
};
std::vector<DepthSpan> depth_spans(const ScreenScene& ss, int threads) {
  const int n = static_cast<int>(ss.curves.size());
  std::vector<DepthSpan> span(static_cast<std::size_t>(n));
  parallel_chunks(n, 16384, threads, [&](int, Chunk r) {
    for (int i = r.begin; i < r.end; ++i) {
      const Curve& c = ss.curves[static_cast<std::size_t>(i)];
      DepthSpan& d = span[static_cast<std::size_t>(i)];
      d = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN(), {-1, -1}, false};
      if (c.sharers.size() > 2) continue;
      const Interval zs = ss.z_of(*c.s), zt = ss.z_of(*c.t);
      d.lo = std::min(zs.inf(), zt.inf());
      d.hi = std::max(zs.sup(), zt.sup());
      for (std::size_t k = 0; k < c.sharers.size(); ++k)
        d.face[k] = ss.brief(static_cast<std::size_t>(c.sharers[k])).face;
      d.covered = c.covered;
    }
  });
  return span;
}

// Two curves, one wholly nearer than the other (their depth ranges apart: on a
// straight curve depth is affine, between its ends' depths), the nearer one
// covered, and no face of its two facets a face of the farther one. Where they
// cross properly on screen, the nearer one's two facets hide the farther one
// on both sides (a face hides no edge of its own: hence no common face, as
// where a fan folds over its own edge), so its visibility does not change
// there; and the farther one's facets, at its depth there, neither hide the
// nearer one nor lie beside it where it is seen (its own facets do). No map
// vertex, no change of visibility or of the faces beside either: their
// crossing needs no point. (But where they overlap, a line right behind
// another on screen lies in no facet's interior and is visible; and where one
// ends on the other, Cutter cuts as ever.)
bool apart(const DepthSpan& a, const DepthSpan& b) {
  const DepthSpan* nearer = a.hi < b.lo ? &a : b.hi < a.lo ? &b : nullptr;   // (NaNs: neither)
  if (nearer == nullptr || !nearer->covered) return false;
  const DepthSpan& farther = nearer == &a ? b : a;
  for (int f : nearer->face)
    if (f == farther.face[0] || f == farther.face[1]) return false;
  return true;
}

}  // namespace

namespace {

// The vertices (canonical ids, ascending) where two drawn curves with one
// faces list end. Only there can two drawn lines join into one segment of a
// lines-only drawing (a map vertex where exactly two edges meet, collinear,
// drawn with the same kind and faces, is not a vertex: the spec's canonical
// form): elsewhere the vertex is one whatever else ends there, and a curve
// that is not drawn and only ends there changes no segment. Only the ends of
// curves that are not drawn are asked about (where every line is drawn, as at
// crease 0, sorting every drawn end was ~3 % of the bunny's drawing).
std::vector<VertexId> joinable_ends(const std::vector<Curve>& curves) {
  std::vector<VertexId> asked;   // (ends of curves not drawn)
  for (const Curve& c : curves)
    if (!c.drawn)
      for (const VertexId v : {c.vs, c.vt})
        if (v >= 0) asked.push_back(v);
  std::sort(asked.begin(), asked.end());
  asked.erase(std::unique(asked.begin(), asked.end()), asked.end());
  std::vector<std::pair<VertexId, const SmallInts*>> ends;   // (vertex, a drawn curve's faces)
  for (const Curve& c : curves)
    if (c.drawn)
      for (const VertexId v : {c.vs, c.vt})
        if (v >= 0 && std::binary_search(asked.begin(), asked.end(), v)) ends.emplace_back(v, &c.faces);
  std::sort(ends.begin(), ends.end(), [](const auto& x, const auto& y) {
    return x.first != y.first ? x.first < y.first : *x.second < *y.second;
  });
  std::vector<VertexId> joinable;
  for (std::size_t i = 1; i < ends.size(); ++i)
    if (ends[i - 1].first == ends[i].first && *ends[i - 1].second == *ends[i].second &&
        (joinable.empty() || joinable.back() != ends[i].first))
      joinable.push_back(ends[i].first);
  return joinable;
}

// The curves that are not drawn and cross a drawn one properly where another
// such curve may cross it too (their crossings' boxes meet: exact points that
// are one have boxes that meet), in no order.
std::vector<int> crossing_others_there(std::vector<DrawnCrossed> crossed) {
  std::sort(crossed.begin(), crossed.end(), [](const DrawnCrossed& x, const DrawnCrossed& y) {
    return x.drawn != y.drawn ? x.drawn < y.drawn : x.box.xmin() < y.box.xmin();
  });
  std::vector<int> found;
  for (std::size_t i = 0; i < crossed.size(); ++i)
    for (std::size_t j = i + 1; j < crossed.size() && crossed[j].drawn == crossed[i].drawn &&
                                crossed[j].box.xmin() <= crossed[i].box.xmax(); ++j)
      if (crossed[j].other != crossed[i].other && CGAL::do_overlap(crossed[i].box, crossed[j].box)) {
        found.push_back(crossed[i].other);
        found.push_back(crossed[j].other);
      }
  return found;
}

}  // namespace

// Step 8: in each cell, every pair of curves; an intersection counts in the cell
// holding it (half-open cells), so each is found once; the crossings of curves
// apart() are not cut.
Cuts cut_curves(Grid& g, const ScreenScene& ss, bool regions, int threads, Stats& stats) {
  const std::size_t n = ss.curves.size();
  Cuts cuts;
  cuts.list_of.assign(n, Cuts::kNone);
  cuts.needed.assign(n, 1);
  std::vector<std::pair<int, int>> overlaps;
  std::vector<DrawnCrossed> crossed;   // (lines only)
  std::int64_t pairs = 0, crossings = 0, uncut = 0, behind = 0;
  // visit(cutter, cell) for every cell, the rows in parallel; what they found is
  // joined in row order, as one pass over the cells in order would have found it.
  auto each_cell = [&](auto&& visit) {
    std::vector<RowCuts> rows(static_cast<std::size_t>(g.Y.cells()));
    parallel_for(g.Y.cells(), threads, [&](int iy) {
      RowCuts found;   // (filled here, stored once: rows side by side share cache lines)
      Cutter cutter{g, ss, found, 0, iy};
      for (int ix = 0; ix < g.X.cells(); ++ix) {
        cutter.ix = ix;
        visit(cutter, g.at(ix, iy));
      }
      rows[static_cast<std::size_t>(iy)] = std::move(found);
    });
    for (RowCuts& row : rows) {
      for (auto& [c, p] : row.at) cuts.at(c).push_back(std::move(p));
      overlaps.insert(overlaps.end(), row.overlaps.begin(), row.overlaps.end());
      for (int c : row.met) cuts.needed[static_cast<std::size_t>(c)] = 1;
      crossed.insert(crossed.end(), row.crossed.begin(), row.crossed.end());
      pairs += row.pairs;
      crossings += row.crossings;
      uncut += row.uncut;
      behind += row.behind;
      row = RowCuts();
    }
  };
  // A curve none of whose facets hides anything is cut where it pierces one.
  auto pierce = [&](Cutter& cutter, const Cell& cell, int ci) {
    const Curve& cv = ss.curves[ci];
    if (std::any_of(cv.sharers.begin(), cv.sharers.end(), [&](int s) { return ss.brief(s).occluder; })) return;
    for (int fi : cell.facets) cutter.pierce(ci, fi);
    if (cell.blocker >= 0) cutter.pierce(ci, cell.blocker);
  };
  const std::vector<DepthSpan> span = depth_spans(ss, threads);
  auto is_apart = [&](int a, int b) {
    return apart(span[static_cast<std::size_t>(a)], span[static_cast<std::size_t>(b)]);
  };
  // A cell's pairs that `wanted(a, b)`, met(a, b, how) where they may meet: on
  // the points' intervals first, one rounding switch per cell.
  auto each_pair = [&](Cutter& cutter, const Cell& cell, auto&& wanted, auto&& met) {
    const auto& cs = cell.curves;
    if (cs.size() < 2) return;
    UpwardRounding upward;
    cutter.start_cell(cell);
    for (std::size_t i = 0; i < cs.size(); ++i)
      for (std::size_t j = i + 1; j < cs.size(); ++j) {
        const int a = cs[i], b = cs[j];
        if (!wanted(a, b) || cutter.known_hidden(i) || cutter.known_hidden(j) || !cutter.boxes_meet(a, b)) continue;
        if (const Contact how = cutter.meet_on_intervals_first(i, j, is_apart(a, b)); how != Contact::kNone) met(a, b, how);
      }
  };
  if (regions) {
    each_cell([&](Cutter& cutter, const Cell& cell) {
      each_pair(cutter, cell, [](int, int) { return true; }, [](int, int, Contact) {});
      for (int ci : cell.curves) pierce(cutter, cell, ci);
    });
  } else {
    // The drawn lines alone (Franklin's step 8 iv-v): every pair with a drawn
    // curve. A curve that is not drawn but meets a drawn one may be needed too
    // (a region boundary ending there splits the drawn line's segment; a
    // nearer seam over it hides it): it is then cut against every curve, as
    // for the whole map, so that its pieces and their labels are the same.
    // Pairs of other curves that are not drawn are never looked at. Not
    // needed for a drawn line:
    // - a curve crossing it apart (apart(): that changes nothing);
    // - one that only shares an end point with it where no two drawn lines
    //   could join (joinable_ends): that is a vertex whatever else ends there;
    // - one that crosses it properly at a point no other such curve crosses it
    //   at (else crossing_others_there). The drawn line is cut there anyway.
    //   Where the crossing curve is seen beside that point and bounds regions
    //   there, the faces on its two sides differ, and so do those beside the
    //   drawn line's two pieces on that side (their labels, told by the facets
    //   alone): the point is a vertex of the map with or without the curve.
    //   Where it is not, it changes nothing. (Two such curves through one point
    //   could bound a region between them, the same face outside the pair.)
    std::vector<char> drawn(n);
    for (std::size_t c = 0; c < n; ++c) drawn[c] = ss.curves[c].drawn;
    cuts.needed = drawn;
    const std::vector<VertexId> joinable = joinable_ends(ss.curves);
    auto at_joinable_end = [&](int a, int b) {
      const VertexId v = Cutter::common_end(ss.curves[a], ss.curves[b])->ip;
      return v < 0 || std::binary_search(joinable.begin(), joinable.end(), v);
    };
    each_cell([&](Cutter& cutter, const Cell& cell) {
      each_pair(cutter, cell, [&](int a, int b) { return drawn[a] || drawn[b]; }, [&](int a, int b, Contact how) {
        if (drawn[a] && drawn[b]) return;   // (both needed already)
        if (how == Contact::kSharedEnd && !at_joinable_end(a, b)) return;
        if (how == Contact::kCrossing && drawn[a] != drawn[b]) {
          // (Counted in the cell holding it, as the cut is; its box as made here,
          // before any other thread sees the point: the same on every thread count.)
          if (cutter.crossing)
            cutter.row.crossed.push_back({drawn[a] ? a : b, drawn[a] ? b : a, cutter.crossing->bbox()});
          return;
        }
        cutter.row.met.push_back(a);
        cutter.row.met.push_back(b);
      });
    });
    for (const int c : crossing_others_there(std::move(crossed))) cuts.needed[static_cast<std::size_t>(c)] = 1;
    bucket_needed_curves(g, ss, cuts.needed, threads);
    each_cell([&](Cutter& cutter, const Cell& cell) {
      const auto& cs = cell.curves;
      each_pair(cutter, cell, [&](int a, int b) { return !drawn[a] && !drawn[b] && (cuts.needed[a] || cuts.needed[b]); },
                [](int, int, Contact) {});
      for (int ci : cs)
        if (cuts.needed[ci]) pierce(cutter, cell, ci);
    });
    stats.count("curves_needed", std::count(cuts.needed.begin(), cuts.needed.end(), 1));
  }
  share_overlap_cuts(ss.curves, overlaps, [&](int c) { return cuts.find(c); },
                     [&](int c, auto first, auto last) {
                       std::vector<P2>& list = cuts.at(c);
                       list.insert(list.end(), first, last);
                     });
  // The cells' curve lists have served (step 9 looks up facets alone): freed
  // before the pieces are made, the peak of a large scene's run.
  parallel_chunks(static_cast<int>(g.cells.size()), 4096, threads, [&](int, Chunk r) {
    for (int k = r.begin; k < r.end; ++k) std::vector<int>().swap(g.cells[static_cast<std::size_t>(k)].curves);
  });
  stats.count("edge_pairs_tested", pairs);
  stats.count("intersections", crossings);
  stats.count("crossings_left_uncut", uncut);   // (pairs apart(): a crossing, if any, cuts nothing)
  stats.count("curve_cells_behind_facet", behind);   // (asked of curves that may cross another)
  stats.count("overlapping_curve_pairs", static_cast<std::int64_t>(overlaps.size()));
  return cuts;
}

namespace {

// What one facet contributes at a point m of a curve: whether it covers the
// points just left / right of m.
struct Cover {
  int facet;
  bool left, right;
};

// `own`: the facet's edge that holds the curve (m is on its line), or -1.
bool cover_at(const Facet& f, Probe& probe, Cover& out, int own) {
  const std::size_t n = f.v.size();
  bool left = true, right = true;
  // m on the border of f, on an edge across the curve: a crossing left uncut
  // (cut_curves) lies right at m, which then tells nothing of either side.
  bool across = false;
  for (std::size_t k = 0; k < n && (left || right || across); ++k) {
    const P3& p = f.v[k];
    const P3& q = f.v[(k + 1) % n];
    const bool held = static_cast<int>(k) == own;
    int o = held ? 0 : orientation(p, q, f.id[k], f.id[(k + 1) % n], probe) * turn(f);
    if (o > 0) continue;
    if (o < 0) return false;
    if (!held && edge_across(p, q, f.id[k], f.id[(k + 1) % n], probe) != CGAL::ZERO) {
      across = true;
      continue;
    }
    // m on this edge's line: the facet lies on one side of it. Which side of the
    // curve that is follows from the edge's direction relative to the curve's.
    int s = edge_along(p, q, probe) * turn(f);
    if (s <= 0) left = false;
    if (s >= 0) right = false;
  }
  if (across) probe.on_crossing_line = true;
  if (across || (!left && !right)) return false;
  out.facet = -1;
  out.left = left;
  out.right = right;
  return true;
}

// Order just beside m on one side: depth, then how fast depth grows that way, then index.
bool before(const Facet& x, const Facet& y, Probe& m, bool left_side) {
  CGAL::Sign c = depth_order(x, y, m);
  if (c != CGAL::ZERO) return c == CGAL::NEGATIVE;
  c = left_side ? slope_order(x, y, m) : slope_order(y, x, m);
  if (c != CGAL::ZERO) return c == CGAL::NEGATIVE;
  return x.face < y.face;
}

}  // namespace

// Steps 9 and 11: cut each curve at its sorted cut points; decide each piece at its
// midpoint against the facets of the midpoint's cell: is it visible, which faces are
// nearest on each side, and does this curve bound a region there.
namespace {

// What classify_curve gives: its pieces worth keeping (visible or bounding a
// region), in order along the curve, and counts.
struct Classified {
  std::vector<VisiblePiece> out;
  std::int64_t pieces = 0, visible = 0;
};

bool decide_piece(const Grid& g, const ScreenScene& ss, int ci, const P2& a, const P2& b, Probe& probe,
                  std::vector<Cover>& covers, Classified& res);

// Steps 9 and 11 for curve ci, cut at pts (sorted here).
void classify_curve(const Grid& g, const ScreenScene& ss, int ci, std::vector<P2>& pts, std::vector<Cover>& covers,
                    Classified& res) {
  const Curve& cv = ss.curves[ci];
  const P2 &s = cv.s->xy(), &t = cv.t->xy();
  // 9a: sort along the curve (the order of the dominant coordinate).
  const bool use_x = mostly_along_x(cv);
  const bool increasing = (use_x ? CGAL::compare(cv.s->x, cv.t->x) : CGAL::compare(cv.s->y, cv.t->y)) == CGAL::SMALLER;
  auto key_less = [&](const P2& a, const P2& b) {   // predicates: no coordinates built
    if (same_rep(a, b)) return false;   // (a point cut twice is often one number)
    return compare_coordinate_exactly(a, b, use_x) == (increasing ? CGAL::SMALLER : CGAL::LARGER);
  };
  // The cut points are shared with the curves cut at them, classified on other
  // threads, and a lazy point's interval narrows once its exact value is known:
  // whether the filter settles a comparison of them depends on which thread got
  // there first, so these comparisons are not counted (the stats must not
  // depend on the thread count).
  const exact::FilterCounts before_sort = exact::filter_counts;
  std::sort(pts.begin(), pts.end(), key_less);
  // Points of one curve are equal when their dominant coordinates are.
  auto same_key = [&](const P2& a, const P2& b) {
    return same_rep(a, b) || compare_coordinate_exactly(a, b, use_x) == CGAL::EQUAL;
  };
  pts.erase(std::unique(pts.begin(), pts.end(), same_key), pts.end());
  exact::filter_counts = before_sort;
  pts.insert(pts.begin(), s);
  pts.push_back(t);
  Probe probe = probe_of(ss, cv);
  std::optional<P2> nearer;   // (a point a piece is decided at instead of its midpoint: made only then)
  UpwardRounding upward;   // the loop calls only our own filtered predicates
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
    ++res.pieces;
    // The piece is decided at its midpoint, or where that lies on a line across
    // it (a crossing left uncut: the piece is the same on both sides of it), at
    // the midpoint of its first half, and so on (finitely many lines cross it).
    const P2* end = &pts[k + 1];
    for (;;) {
      probe.at_midpoint(pts[k], *end);
      probe.on_crossing_line = false;
      if (decide_piece(g, ss, ci, pts[k], pts[k + 1], probe, covers, res)) break;
      NearestRounding nearest;   // (a lazy construction: CGAL rounds to nearest)
      nearer = CGAL::midpoint(pts[k], *end);
      end = &*nearer;
    }
  }
}

// Steps 9c and 11 for the piece a-b of curve ci at the probe's point: false
// where that point lies on a line across the piece (Probe::on_crossing_line),
// which tells nothing; else true, the piece kept in `res` if it is visible or
// bounds a region.
bool decide_piece(const Grid& g, const ScreenScene& ss, int ci, const P2& a, const P2& b, Probe& probe,
                  std::vector<Cover>& covers, Classified& res) {
  const Curve& cv = ss.curves[ci];
  const Cell& cell = g.at(cell_index_of(g.X, probe.ix, [&] { probe.need_exact(); return probe.ex; }),
                    cell_index_of(g.Y, probe.iy, [&] { probe.need_exact(); return probe.ey; }));
  covers.clear();
  const CGAL::Bbox_2 mbox(probe.ix.inf(), probe.iy.inf(), probe.ix.sup(), probe.iy.sup());
  // A facet of another face covering both sides of m strictly in front of
  // the curve hides the piece, and no facet holding the curve (at the
  // curve's depth) can then be nearest on either side: the piece is neither
  // drawn nor a region boundary, and the rest of its cell need not be seen.
  auto hides = [&](int fi, const Cover& c) {
    return c.left && c.right && !std::binary_search(cv.faces.begin(), cv.faces.end(), ss.facet(fi).face) &&
           depth_against_curve(ss.facet(fi), probe) == CGAL::NEGATIVE;
  };
  auto consider = [&](int fi) {   // true: fi hides the piece
    if (!CGAL::do_overlap(mbox, ss.facet(fi).box)) return false;   // cheap: cannot cover m
    int own = -1;
    for (std::size_t j = 0; j < cv.sharers.size(); ++j)
      if (cv.sharers[j] == fi) own = cv.sharer_edge[j];
    Cover c;
    if (!cover_at(ss.facet(fi), probe, c, own)) return false;
    c.facet = fi;
    covers.push_back(c);
    return hides(fi, c);
  };
  bool hidden = false;
  for (int fi : cell.facets)
    if ((hidden = consider(fi)) || probe.on_crossing_line) break;
  if (!hidden && !probe.on_crossing_line && cell.blocker >= 0) hidden = consider(cell.blocker);
  if (probe.on_crossing_line) return false;
  if (hidden) return true;
  // Nearest face on each side (step 11).
  int bl = -1, br = -1;
  for (std::size_t i = 0; i < covers.size(); ++i) {
    const Facet& f = ss.facet(covers[i].facet);
    if (covers[i].left && (bl < 0 || before(f, ss.facet(covers[bl].facet), probe, true))) bl = static_cast<int>(i);
    if (covers[i].right && (br < 0 || before(f, ss.facet(covers[br].facet), probe, false))) br = static_cast<int>(i);
  }
  VisiblePiece vp;
  vp.a = a;
  vp.b = b;
  vp.curve = ci;
  vp.left = bl < 0 ? -1 : ss.facet(covers[bl].facet).face;
  vp.right = br < 0 ? -1 : ss.facet(covers[br].facet).face;
  if (vp.left != vp.right) {
    auto responsible = [&](int i) {
      return i >= 0 && std::find(cv.sharers.begin(), cv.sharers.end(), covers[i].facet) != cv.sharers.end();
    };
    vp.boundary = cv.kind == EdgeKind::Intersection && cv.drawn ? (responsible(bl) && responsible(br))
                                                                 : (responsible(bl) || responsible(br));
  }
  // 9c: visible unless a face not sharing the curve covers both sides of m and
  // comes before it in (depth, face index). Edge pieces that are not drawn
  // (smooth) too: where lines coincide, the first visible one decides.
  if (!cv.faces.empty()) {
    vp.visible = true;
    for (std::size_t i = 0; i < covers.size() && vp.visible; ++i) {
      const int face = ss.facet(covers[i].facet).face;
      if (std::binary_search(cv.faces.begin(), cv.faces.end(), face)) continue;
      auto c = depth_against_curve(ss.facet(covers[i].facet), probe);
      if (!(c == CGAL::NEGATIVE || (c == CGAL::ZERO && face < cv.order_face))) continue;
      bool both = covers[i].left && covers[i].right;
      // Two facets of one (fanned) polygon covering the two sides hide it only
      // where they meet at m: the same depth there. A facet of that polygon
      // further back, a fold's other layer, does not continue this one.
      for (std::size_t j = 0; j < covers.size() && !both; ++j)
        if (j != i && ss.facet(covers[j].facet).face == face &&
            (covers[i].left || covers[j].left) && (covers[i].right || covers[j].right))
          both = depth_order(ss.facet(covers[i].facet), ss.facet(covers[j].facet), probe) == CGAL::ZERO;
      if (both) vp.visible = false;
    }
  }
  res.visible += vp.visible && cv.drawn;
  if (vp.visible || vp.boundary) res.out.push_back(std::move(vp));
  return true;
}

}  // namespace

PieceChunks classify_pieces(const Grid& g, const ScreenScene& ss, Cuts& cuts, int threads, Stats& stats) {
  // Chunks of consecutive curves, classified in parallel; the chunks in order
  // hold the pieces in curve order, the same for every thread count.
  const int n = static_cast<int>(ss.curves.size()), size = 256;
  std::vector<Classified> chunks(static_cast<std::size_t>(chunk_count(n, size)));
  parallel_chunks(n, size, threads, [&](int k, Chunk r) {
    std::vector<Cover> covers;
    std::vector<P2> uncut;   // (the list of a curve cut nowhere)
    Classified found;        // (filled here, stored once: chunks side by side share cache lines)
    for (int ci = r.begin; ci < r.end; ++ci) {
      if (!cuts.needed[static_cast<std::size_t>(ci)]) continue;
      std::vector<P2>* own = cuts.find(ci);
      if (!own) uncut.clear();
      classify_curve(g, ss, ci, own ? *own : uncut, covers, found);
    }
    chunks[static_cast<std::size_t>(k)] = std::move(found);
  });
  PieceChunks out(chunks.size());
  std::int64_t pieces = 0, visible = 0;
  for (std::size_t k = 0; k < chunks.size(); ++k) {
    pieces += chunks[k].pieces;
    visible += chunks[k].visible;
    out[k] = std::move(chunks[k].out);
  }
  stats.count("pieces", pieces);
  stats.count("visible_pieces", visible);
  return out;
}

VISMAP_KERNEL_END
}  // namespace vismap::engine
