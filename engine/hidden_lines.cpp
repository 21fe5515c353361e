// Hidden lines, exactly (spec: "hidden"). A point of a drawn edge piece or
// intersection line is hidden where it is not visible and no visible segment
// lies over it. The visible map already says where lines are visible: a visible
// line is drawn as a segment, unless the first visible line there is a smooth
// seam that is not drawn. So on each screen line (the pieces and segments that
// are collinear, grouped exactly), a stretch of a piece is hidden where no
// segment covers it, except where an undrawn seam lies on it too: there the
// piece's own visibility is decided, from the faces around it. Coinciding hidden
// pieces give one segment, of the first in the order (depth, face index), and
// stretches of one kind and faces list are joined into maximal segments.
#include "engine/hidden_lines.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <mutex>
#include <numeric>
#include <unordered_map>

#include "engine/engine_run.h"
#include "engine/franklin_grid.h"
#include "engine/parallel.h"
#include "engine/screen_scene.h"

namespace vismap::engine {
VISMAP_KERNEL_BEGIN
namespace {

// A uniform grid over the screen boxes of the facets that hide (not edge-on, in
// front of the near plane): the facets that may hold a point or cross a stretch.
// Doubles only choose cells: the boxes contain the exact projections.
class FacetGrid {
 public:
  explicit FacetGrid(const std::vector<Facet>& facets) {
    CGAL::Bbox_2 all;
    for (std::size_t fi = 0; fi < facets.size(); ++fi)
      if (hides(facets[fi])) {
        all += facets[fi].box;
        members_.push_back(static_cast<int>(fi));
      }
    x0_ = all.xmin();
    y0_ = all.ymin();
    n_ = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(members_.size()))), 1, 1024);
    w_ = (all.xmax() - x0_) / n_;
    h_ = (all.ymax() - y0_) / n_;
    cells_.resize(static_cast<std::size_t>(n_) * n_);
    for (int fi : members_) {
      const Range r = range(facets[static_cast<std::size_t>(fi)].box);
      for (int iy = r.y0; iy <= r.y1; ++iy)
        for (int ix = r.x0; ix <= r.x1; ++ix) cells_[static_cast<std::size_t>(iy) * n_ + ix].push_back(fi);
    }
  }
  static bool hides(const Facet& f) { return !f.v.empty() && f.facing != Facing::EdgeOn; }

  struct Range {
    int x0, y0, x1, y1;
  };
  Range range(const CGAL::Bbox_2& b) const {
    return {cell(b.xmin(), x0_, w_), cell(b.ymin(), y0_, h_), cell(b.xmax(), x0_, w_), cell(b.ymax(), y0_, h_)};
  }
  const std::vector<int>& at(int ix, int iy) const { return cells_[static_cast<std::size_t>(iy) * n_ + ix]; }
  // The facets listed in the cells a box meets, each once, in index order.
  std::vector<int> near(const CGAL::Bbox_2& b) const {
    std::vector<int> out;
    const Range r = range(b);
    for (int iy = r.y0; iy <= r.y1; ++iy)
      for (int ix = r.x0; ix <= r.x1; ++ix) out.insert(out.end(), at(ix, iy).begin(), at(ix, iy).end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

 private:
  int cell(double v, double lo, double size) const {
    if (!(size > 0)) return 0;
    return std::clamp(static_cast<int>(std::floor((v - lo) / size)), 0, n_ - 1);
  }
  std::vector<int> members_;
  std::vector<std::vector<int>> cells_;
  double x0_ = 0, y0_ = 0, w_ = 0, h_ = 0;
  int n_ = 1;
};

// The facets that may pierce each other, found in the world, where a mesh's
// facets are of similar size whatever the view (on the screen a close-up's near
// facets cover thousands of times more): a hash grid of cubes about a facet's
// size, each facet listed in the cubes of its box.
class WorldGrid {
 public:
  using Box = std::array<double, 6>;   // x0 y0 z0 x1 y1 z1
  WorldGrid(const WorldFacets& wf, const std::vector<Vec3>& input, const std::vector<char>& listed) {
    box_.resize(wf.facets.size());
    std::vector<double> extent;
    for (std::size_t fi = 0; fi < wf.facets.size(); ++fi) {
      if (!listed[fi]) continue;
      Box& b = box_[fi];
      b = {HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
      for (std::uint32_t id : wf.facets[fi].v) {
        const Vec3& p = input[id];
        const double c[3] = {p.x, p.y, p.z};
        for (int a = 0; a < 3; ++a) {
          b[a] = std::min(b[a], c[a]);
          b[a + 3] = std::max(b[a + 3], c[a]);
        }
      }
      extent.push_back(std::max({b[3] - b[0], b[4] - b[1], b[5] - b[2]}));
    }
    if (extent.empty()) return;
    std::nth_element(extent.begin(), extent.begin() + static_cast<std::ptrdiff_t>(extent.size() / 2), extent.end());
    size_ = extent[extent.size() / 2];
    if (!(size_ > 0) || !std::isfinite(size_)) size_ = 1;
    for (std::size_t fi = 0; fi < wf.facets.size(); ++fi) {
      if (!listed[fi]) continue;
      if (many_cells(box_[fi])) big_.push_back(static_cast<int>(fi));
      else for_cells(box_[fi], [&](const Cube& c) { cells_[c].push_back(static_cast<int>(fi)); });
    }
  }
  // Facets far larger than the median (a ground plane, a huge backdrop), in no
  // cube: each is tested against every other listed facet instead.
  const std::vector<int>& big() const { return big_; }
  const Box& box(int fi) const { return box_[static_cast<std::size_t>(fi)]; }
  static bool meet(const Box& a, const Box& b) {
    return a[0] <= b[3] && b[0] <= a[3] && a[1] <= b[4] && b[1] <= a[4] && a[2] <= b[5] && b[2] <= a[5];
  }
  using Cube = std::array<std::int64_t, 3>;
  struct CubeHash {
    std::size_t operator()(const Cube& c) const {
      std::uint64_t k = 0;
      for (std::int64_t x : c) k = (k ^ static_cast<std::uint64_t>(x)) * 0x9E3779B97F4A7C15ull;
      return static_cast<std::size_t>(k ^ (k >> 29));
    }
  };
  // Whether `cube` is the first that both boxes reach (each pair tested once).
  bool first_common(const Box& a, const Box& b, const Cube& cube) const {
    return Cube{cell(std::max(a[0], b[0])), cell(std::max(a[1], b[1])), cell(std::max(a[2], b[2]))} == cube;
  }
  const std::unordered_map<Cube, std::vector<int>, CubeHash>& cells() const { return cells_; }

 private:
  std::int64_t cell(double v) const { return static_cast<std::int64_t>(std::floor(v / size_)); }
  // More than 64 cubes, or cube indices beyond 2^62 (coordinates far larger than
  // the facets: 1e300 against 1e-9).
  bool many_cells(const Box& b) const {
    double count = 1;
    for (int a = 0; a < 3; ++a) {
      const double lo = std::floor(b[a] / size_), hi = std::floor(b[a + 3] / size_);
      if (!(std::abs(lo) < 0x1p62 && std::abs(hi) < 0x1p62)) return true;
      count *= hi - lo + 1;
    }
    return count > 64;
  }
  template <class F>
  void for_cells(const Box& b, F&& f) const {
    for (std::int64_t x = cell(b[0]); x <= cell(b[3]); ++x)
      for (std::int64_t y = cell(b[1]); y <= cell(b[4]); ++y)
        for (std::int64_t z = cell(b[2]); z <= cell(b[5]); ++z) f(Cube{x, y, z});
  }
  std::vector<Box> box_;
  std::vector<int> big_;
  double size_ = 1;
  std::unordered_map<Cube, std::vector<int>, CubeHash> cells_;
};

// Faces that pierce each other, all of them (hidden ones too): an intersection
// line for every pair of facets of different faces that cross strictly inside
// both projections, as the engines find the visible ones; lines in the order of
// their pairs.
void add_all_intersection_lines(ScreenScene& ss, const WorldFacets& wf, int threads) {
  struct Crossing {
    int fa, fb;
    P2 p, q;
  };
  std::vector<char> listed(ss.facets.size());
  for (std::size_t fi = 0; fi < ss.facets.size(); ++fi) listed[fi] = FacetGrid::hides(ss.facets[fi]);
  const WorldGrid grid(wf, *ss.world, listed);
  const EmbeddedStars stars(ss, threads);
  auto test = [&](int fa, int fb, std::vector<Crossing>& out) {   // (fa < fb)
    const Facet &A = ss.facets[static_cast<std::size_t>(fa)], &B = ss.facets[static_cast<std::size_t>(fb)];
    if (A.face == B.face || !WorldGrid::meet(grid.box(fa), grid.box(fb))) return;
    if (!CGAL::do_overlap(A.box, B.box) || cannot_pierce(A, B, stars)) return;
    P2 p, q;
    if (intersection_segment(A, B, ss.world, p, q)) out.push_back(Crossing{fa, fb, p, q});
  };
  // The cubes, then the facets far larger than the median, in chunks on the threads.
  std::vector<std::pair<const WorldGrid::Cube*, const std::vector<int>*>> cubes;
  for (const auto& [cube, in] : grid.cells()) cubes.emplace_back(&cube, &in);
  const std::vector<int>& big = grid.big();
  const int nc = static_cast<int>(cubes.size()), nb = static_cast<int>(big.size());
  const int size = 512, cube_chunks = chunk_count(nc, size);
  std::vector<Crossing> found;
  parallel_append(found, cube_chunks + nb, threads, [&](int k, std::vector<Crossing>& out) {
    if (k >= cube_chunks) {   // a big facet against every other listed one
      const int b = big[static_cast<std::size_t>(k - cube_chunks)];
      for (std::size_t fi = 0; fi < listed.size(); ++fi) {
        const int f = static_cast<int>(fi);
        if (!listed[fi] || f == b || (std::binary_search(big.begin(), big.end(), f) && f < b)) continue;
        test(std::min(b, f), std::max(b, f), out);
      }
      return;
    }
    const Chunk r = chunk(k, nc, size);
    for (int c = r.begin; c < r.end; ++c) {
      const auto& [cube, in] = cubes[static_cast<std::size_t>(c)];
      for (std::size_t i = 0; i < in->size(); ++i)
        for (std::size_t j = i + 1; j < in->size(); ++j) {
          const int fa = std::min((*in)[i], (*in)[j]), fb = std::max((*in)[i], (*in)[j]);
          if (grid.first_common(grid.box(fa), grid.box(fb), *cube)) test(fa, fb, out);
        }
    }
  });
  // (In the order of their pairs: the same for every thread count.)
  parallel_sort(found.begin(), found.end(),
                [](const Crossing& x, const Crossing& y) { return std::pair(x.fa, x.fb) < std::pair(y.fa, y.fb); },
                threads);
  std::deque<P3>& line_ends = ss.ends.emplace_back();
  for (const Crossing& c : found) {
    ss.curves.push_back(crossing_curve(ss.facets[static_cast<std::size_t>(c.fa)], ss.facets[static_cast<std::size_t>(c.fb)],
                                       c.fa, c.fb, c.p, c.q, line_ends));
  }
}

// What lies on one screen line: a drawn piece (a candidate hidden line), an
// undrawn smooth seam, or a visible segment of the map.
enum class Role : std::uint8_t { Drawn, Seam, Segment };
struct Item {
  P2 lo, hi;      // lo < hi, lexicographically (so: in order along the line)
  int curve;      // the curve (-1 for a segment)
  Role role;
};

Item item(const P2& a, const P2& b, int curve, Role role) {
  if (compare_xy_exactly(a, b) == CGAL::LARGER) return Item{b, a, curve, role};
  return Item{a, b, curve, role};
}

// Whether two items lie on one screen line, exactly.
bool same_line(const Item& a, const Item& b) {
  return CGAL::orientation(a.lo, a.hi, b.lo) == CGAL::COLLINEAR && CGAL::orientation(a.lo, a.hi, b.hi) == CGAL::COLLINEAR;
}

// Interval keys of an item's screen line that hold exact values equal for equal
// lines: its direction (lo -> hi) over its L1 norm, y part, and its offset
// x ny - y nx. Lines whose keys are apart are different, told on intervals.
struct LineKey {
  Interval slope, offset;
};
// The same keys from the ends' exact values, as the tightest intervals around
// them: for an item so short that its ends' intervals overlap (its direction,
// on intervals, any), whose key would otherwise be unbounded and overlap every
// other, making all the items one cluster, tested pairwise (a map segment of
// CGAL's cheese.off: 33 144 items, 11 s).
LineKey exact_key_of(const Item& it) {
  const mpq_class x0 = exact_x(it.lo), y0 = exact_y(it.lo);
  const mpq_class dx = exact_x(it.hi) - x0, dy = exact_y(it.hi) - y0;
  const mpq_class norm = abs(dx) + abs(dy);
  if (sgn(norm) == 0) return {Interval::largest(), Interval::largest()};   // (no line: never two equal ends)
  const mpq_class nx = dx / norm, ny = dy / norm, offset = x0 * ny - y0 * nx;
  return {Interval(CGAL::to_interval(ny)), Interval(CGAL::to_interval(offset))};
}
LineKey key_of(const Item& it) {
  LineKey k;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const Interval x0 = approx_x(it.lo), y0 = approx_y(it.lo);
    const Interval dx = approx_x(it.hi) - x0, dy = approx_y(it.hi) - y0;
    const Interval norm = CGAL::abs(dx) + CGAL::abs(dy);
    const Interval nx = dx / norm, ny = dy / norm;
    k = {ny, x0 * ny - y0 * nx};
  }
  auto bounded = [](const Interval& v) { return std::isfinite(v.inf()) && std::isfinite(v.sup()); };
  return bounded(k.slope) && bounded(k.offset) ? k : exact_key_of(it);
}

// Splits idx[begin, end) into runs whose intervals (key(i)) overlap, one after
// another (sorted by lower end; a run goes on while the next starts before the
// run's highest upper end), calling f(begin, end) on each.
template <class Key, class F>
void overlapping_runs(std::vector<int>& idx, std::size_t begin, std::size_t end, Key&& key, F&& f) {
  std::sort(idx.begin() + static_cast<std::ptrdiff_t>(begin), idx.begin() + static_cast<std::ptrdiff_t>(end),
            [&](int a, int b) { return key(a).inf() < key(b).inf() || (key(a).inf() == key(b).inf() && a < b); });
  for (std::size_t i = begin; i < end;) {
    double hi = key(idx[i]).sup();
    std::size_t j = i + 1;
    while (j < end && !(key(idx[j]).inf() > hi)) hi = std::max(hi, key(idx[j++]).sup());
    f(i, j);
    i = j;
  }
}

// Whether a curve's piece is visible, where an undrawn seam lies over it (the
// one case the map's segments do not answer): by the spec's rule, no face but
// its own holding the point inside its projection and before it in the order
// (depth, face index).
class Visibility {
 public:
  explicit Visibility(const ScreenScene& ss) : ss_(ss) {}

  bool visible(const Curve& c, const P2& p) const {
    const FT depth = depth_on(c, p);
    const std::vector<int> near =
        grid().near(CGAL::Bbox_2(approx_x(p).inf(), approx_y(p).inf(), approx_x(p).sup(), approx_y(p).sup()));
    for (int fi : near) {
      const Facet& f = ss_.facets[static_cast<std::size_t>(fi)];
      if (own(c, f) || !(strictly_inside(f, p) || across_diagonal(f, near, p))) continue;
      const CGAL::Comparison_result order = CGAL::compare(f.depth_at(p), depth);
      if (order == CGAL::SMALLER || (order == CGAL::EQUAL && f.face < c.order_face)) return false;
    }
    return true;
  }

  // Points strictly between a and b on curve c where its visibility may change:
  // where it crosses a facet's projected side or ends on one, and where it passes
  // through a facet's plane.
  void changes(const Curve& c, const P2& a, const P2& b, std::vector<P2>& out) const {
    const CGAL::Bbox_2 box = a.bbox() + b.bbox();
    const FT da = depth_on(c, a), db = depth_on(c, b);
    for (int fi : grid().near(box)) {
      const Facet& f = ss_.facets[static_cast<std::size_t>(fi)];
      if (own(c, f) || !CGAL::do_overlap(f.box, box)) continue;
      const FT ga = f.depth_at(a) - da, gb = f.depth_at(b) - db;
      if (CGAL::sign(ga) * CGAL::sign(gb) < 0) out.push_back(a + (ga / (ga - gb)) * (b - a));
      for (std::size_t k = 0, n = f.v.size(); k < n; ++k) side_crossing(a, b, f.v[k].xy(), f.v[(k + 1) % n].xy(), out);
    }
  }

 private:
  // Whether p lies inside a side of f that another facet of f's face shares (a
  // diagonal inside the polygon: a fan's, or an ear clipping's) and the two lie on
  // either side of it on the screen: then p is inside the face's projection,
  // though on the edge of both facets. Sides are matched by their corners' ids;
  // a diagonal the near plane cut ends at a cut point (no id), matched by its
  // position (both facets cut the diagonal at the same point).
  bool across_diagonal(const Facet& f, const std::vector<int>& near, const P2& p) const {
    const std::size_t n = f.v.size();
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t k1 = (k + 1) % n;
      const P2 &u = f.v[k].xy(), &v = f.v[k1].xy();
      if ((f.id[k] < 0 || f.id[k1] < 0) && !f.on_diagonal(k)) continue;   // (a near-plane cut, or a side cut short)
      if (CGAL::orientation(u, v, p) != CGAL::COLLINEAR) continue;
      if (compare_xy_exactly(p, u) == compare_xy_exactly(p, v)) continue;   // (not between its ends)
      const CGAL::Orientation mine = CGAL::orientation(u, v, f.v[(k + 2) % n].xy());
      for (int gi : near) {
        const Facet& g = ss_.facets[static_cast<std::size_t>(gi)];
        if (&g == &f || g.face != f.face || g.v.empty()) continue;
        for (std::size_t j = 0, m = g.v.size(); j < m; ++j) {
          const std::size_t j1 = (j + 1) % m;
          auto same = [&](std::size_t fk, std::size_t gj) {
            return f.id[fk] >= 0 ? f.id[fk] == g.id[gj] : g.id[gj] < 0 && equal_points(f.v[fk].xy(), g.v[gj].xy());
          };
          if (!((same(k, j) && same(k1, j1)) || (same(k, j1) && same(k1, j)))) continue;
          if (CGAL::orientation(u, v, g.v[(j + 2) % m].xy()) == -mine) return true;
        }
      }
    }
    return false;
  }

  static bool own(const Curve& c, const Facet& f) {
    return std::find(c.faces.begin(), c.faces.end(), f.face) != c.faces.end();
  }
  // Where side u-v meets the open segment a-b: a proper crossing, or an end of
  // the side on it.
  static void side_crossing(const P2& a, const P2& b, const P2& u, const P2& v, std::vector<P2>& out) {
    const CGAL::Orientation ou = CGAL::orientation(a, b, u), ov = CGAL::orientation(a, b, v);
    auto strictly_between = [&](const P2& p) {
      return compare_xy_exactly(a, p) == CGAL::SMALLER && compare_xy_exactly(p, b) == CGAL::SMALLER;
    };
    if (ou == CGAL::COLLINEAR || ov == CGAL::COLLINEAR) {
      if (ou == CGAL::COLLINEAR && strictly_between(u)) out.push_back(u);
      if (ov == CGAL::COLLINEAR && strictly_between(v)) out.push_back(v);
      return;
    }
    if (ou == ov) return;
    const CGAL::Orientation oa = CGAL::orientation(u, v, a), ob = CGAL::orientation(u, v, b);
    if (oa == CGAL::COLLINEAR || ob == CGAL::COLLINEAR || oa == ob) return;
    const V2 ab = b - a, uv = v - u, au = u - a;
    const FT lambda = (au.x() * uv.y() - au.y() * uv.x()) / (ab.x() * uv.y() - ab.y() * uv.x());
    out.push_back(a + lambda * ab);
  }

  // The grid of facets on the screen, made when first asked (most scenes never do).
  const FacetGrid& grid() const {
    std::call_once(made_, [&] { grid_ = std::make_unique<FacetGrid>(ss_.facets); });
    return *grid_;
  }

  const ScreenScene& ss_;
  mutable std::once_flag made_;
  mutable std::unique_ptr<FacetGrid> grid_;
};

// A stretch of hidden line on one screen line, of one curve's kind and faces.
struct Run {
  P2 lo, hi;
  int curve;
};

bool less_xy(const P2& a, const P2& b) { return compare_xy_exactly(a, b) == CGAL::SMALLER; }

// One screen line's items (a group, in any order), swept along the line: its
// stretches between consecutive end points, each with the segments and seams
// over it and the drawn pieces on it.
class LineSweep {
 public:
  LineSweep(const ScreenScene& ss, const std::vector<Item>& items, const std::vector<int>& group, const Visibility& vis)
      : ss_(ss), vis_(vis) {
    for (int i : group) {
      ev_.push_back(items[static_cast<std::size_t>(i)].lo);
      ev_.push_back(items[static_cast<std::size_t>(i)].hi);
    }
    sort_points(ev_);
    const std::size_t m = ev_.size() - 1;
    covered_.assign(m + 1, 0);
    seams_.assign(m + 1, 0);
    drawn_.resize(m);
    for (int i : group) {
      const Item& it = items[static_cast<std::size_t>(i)];
      const std::size_t a = at(it.lo), b = at(it.hi);
      if (it.role == Role::Drawn) {
        for (std::size_t k = a; k < b; ++k) drawn_[k].push_back(it.curve);
      } else {   // (counts: +1 where it starts, -1 where it ends)
        std::vector<int>& count = it.role == Role::Segment ? covered_ : seams_;
        ++count[a];
        --count[b];
      }
    }
    along_x_ = CGAL::compare_x(ev_.front(), ev_.back()) != CGAL::EQUAL;
  }

  // The hidden runs, in order along the line, appended to `out`.
  void runs(std::vector<Run>& out) const {
    int cover = 0, seam = 0;
    bool open = false;   // the last run may go on
    for (std::size_t k = 0; k + 1 < ev_.size(); ++k) {
      cover += covered_[k];
      seam += seams_[k];
      if (cover > 0 || drawn_[k].empty()) { open = false; continue; }
      const std::vector<P2> cut = cuts(k, seam > 0);
      for (std::size_t s = 0; s + 1 < cut.size(); ++s) {
        const int first = first_hidden(k, CGAL::midpoint(cut[s], cut[s + 1]), seam > 0);
        if (first < 0) { open = false; continue; }
        if (open && same_kind_and_faces(out.back().curve, first)) out.back().hi = cut[s + 1];
        else out.push_back(Run{cut[s], cut[s + 1], first});
        open = true;
      }
    }
  }

 private:
  static void sort_points(std::vector<P2>& v) {
    std::sort(v.begin(), v.end(), less_xy);
    auto same = [](const P2& a, const P2& b) { return compare_xy_exactly(a, b) == CGAL::EQUAL; };
    v.erase(std::unique(v.begin(), v.end(), same), v.end());
  }
  std::size_t at(const P2& p) const {
    return static_cast<std::size_t>(std::lower_bound(ev_.begin(), ev_.end(), p, less_xy) - ev_.begin());
  }
  const Curve& curve(int c) const { return ss_.curves[static_cast<std::size_t>(c)]; }

  // Stretch k cut where its first hidden piece may change: where two of its
  // drawn pieces' depths cross, and, under a seam, where their visibility may.
  std::vector<P2> cuts(std::size_t k, bool under_seam) const {
    std::vector<P2> out{ev_[k], ev_[k + 1]};
    const std::vector<int>& d = drawn_[k];
    for (std::size_t i = 0; i < d.size(); ++i) {
      for (std::size_t j = i + 1; j < d.size(); ++j) {
        P2 x;
        if (depth_crossing(curve(d[i]), curve(d[j]), ev_[k], ev_[k + 1], x)) out.push_back(x);
      }
      if (under_seam) vis_.changes(curve(d[i]), ev_[k], ev_[k + 1], out);
    }
    sort_points(out);
    return out;
  }

  // Of stretch k's drawn pieces hidden at p (all of them, unless under a seam),
  // the first in (depth, face index); -1 if none.
  int first_hidden(std::size_t k, const P2& p, bool under_seam) const {
    int first = -1;
    for (int c : drawn_[k]) {
      if (under_seam && vis_.visible(curve(c), p)) continue;
      if (first < 0 || before(c, first, p)) first = c;
    }
    return first;
  }

  // c before d in (depth, face index) at p; where both tie (one 3D line, one
  // lowest face), their faces lists decide, lexicographically.
  bool before(int c, int d, const P2& p) const {
    const CGAL::Sign gap = depth_gap(curve(c), curve(d), p, along_x_);
    if (gap != CGAL::ZERO) return gap < 0;
    const SmallInts &fc = curve(c).faces, &fd = curve(d).faces;
    if (!std::equal(fc.begin(), fc.end(), fd.begin(), fd.end()))
      return std::lexicographical_compare(fc.begin(), fc.end(), fd.begin(), fd.end());
    return c < d;
  }
  bool same_kind_and_faces(int c, int d) const { return curve(c).kind == curve(d).kind && curve(c).faces == curve(d).faces; }

  const ScreenScene& ss_;
  const Visibility& vis_;
  std::vector<P2> ev_;                    // the items' end points, in order along the line
  std::vector<int> covered_, seams_;      // segments and seams starting (+1) and ending (-1) at each
  std::vector<std::vector<int>> drawn_;   // per stretch: the drawn pieces on it
  bool along_x_ = true;                   // (the line is not vertical: depths compared along x)
};

// The clusters of items whose keys overlap in slope and then in offset (equal
// lines always share one), as ranges of `idx`.
std::vector<std::pair<std::size_t, std::size_t>> clusters(const std::vector<LineKey>& keys, std::vector<int>& idx) {
  idx.resize(keys.size());
  std::iota(idx.begin(), idx.end(), 0);
  auto slope = [&](int i) -> const Interval& { return keys[static_cast<std::size_t>(i)].slope; };
  auto offset = [&](int i) -> const Interval& { return keys[static_cast<std::size_t>(i)].offset; };
  std::vector<std::pair<std::size_t, std::size_t>> out;
  overlapping_runs(idx, 0, idx.size(), slope, [&](std::size_t b, std::size_t e) {
    overlapping_runs(idx, b, e, offset, [&](std::size_t b2, std::size_t e2) { out.emplace_back(b2, e2); });
  });
  return out;
}

// The runs of every screen line: items grouped by line, exactly, each group's
// runs in order along it. Intervals of each line's slope and offset sort most
// items apart first; exact tests only among items whose intervals overlap. A
// drawn piece alone on its line is hidden throughout.
std::vector<Run> hidden_runs(const ScreenScene& ss, const std::vector<Item>& items, const Visibility& vis, int threads) {
  std::vector<LineKey> keys(items.size());
  parallel_chunks(static_cast<int>(items.size()), 4096, threads, [&](int, Chunk r) {
    for (int i = r.begin; i < r.end; ++i) keys[static_cast<std::size_t>(i)] = key_of(items[static_cast<std::size_t>(i)]);
  });
  std::vector<int> idx;
  const std::vector<std::pair<std::size_t, std::size_t>> parts = clusters(keys, idx);
  auto at = [&](int i) -> const Item& { return items[static_cast<std::size_t>(i)]; };
  // Chunks of clusters on the threads, their runs appended in cluster order.
  std::vector<Run> runs;
  const int n = static_cast<int>(parts.size()), size = 2048;
  parallel_append(runs, chunk_count(n, size), threads, [&](int k, std::vector<Run>& out) {
    std::vector<int> group, rest;
    auto on_line = [&] {
      if (group.size() == 1) {
        if (at(group[0]).role == Role::Drawn) out.push_back(Run{at(group[0]).lo, at(group[0]).hi, at(group[0]).curve});
        return;
      }
      if (std::any_of(group.begin(), group.end(), [&](int g) { return at(g).role == Role::Drawn; }))
        LineSweep(ss, items, group, vis).runs(out);
    };
    const Chunk r = chunk(k, n, size);
    for (int c = r.begin; c < r.end; ++c) {
      // The lines among a cluster, exactly: each group, the items on its first item's line.
      const auto [b, e] = parts[static_cast<std::size_t>(c)];
      rest.assign(idx.begin() + static_cast<std::ptrdiff_t>(b), idx.begin() + static_cast<std::ptrdiff_t>(e));
      while (!rest.empty()) {
        const int first = rest[0];
        group.assign(1, first);
        std::size_t kept = 0;
        for (std::size_t i = 1; i < rest.size(); ++i) {
          if (same_line(at(first), at(rest[i]))) group.push_back(rest[i]);
          else rest[kept++] = rest[i];
        }
        rest.resize(kept);
        on_line();
      }
    }
  });
  return runs;
}

// The items: every drawn curve and undrawn seam, and the map's segments (scaled
// to the screen scene's coordinates).
std::vector<Item> line_items(const ScreenScene& ss, const VisibilityMap& map) {
  std::vector<Item> items;
  for (std::size_t i = 0; i < ss.curves.size(); ++i) {
    const Curve& c = ss.curves[i];
    if (c.faces.empty()) continue;   // (a near-plane cut: no edge)
    if (c.drawn) items.push_back(item(c.s->xy(), c.t->xy(), static_cast<int>(i), Role::Drawn));
    else if (c.kind == EdgeKind::Smooth) items.push_back(item(c.s->xy(), c.t->xy(), static_cast<int>(i), Role::Seam));
  }
  auto scaled = [&](const Point2& p) {
    mpq_class x = p.x, y = p.y;
    times_pow2(x, ss.scale_exp);
    times_pow2(y, ss.scale_exp);
    return P2(from_mpq(x), from_mpq(y));
  };
  for (const Segment& s : map.segments) items.push_back(item(scaled(map.at(s.from)), scaled(map.at(s.to)), -1, Role::Segment));
  return items;
}

// The runs as the map's hidden segments: exact end points in the spec's
// coordinates, sorted by (from, to). On the threads.
std::vector<HiddenSegment> hidden_segments(const ScreenScene& ss, const std::vector<Run>& runs, int threads) {
  std::vector<HiddenSegment> out(runs.size());
  parallel_chunks(static_cast<int>(runs.size()), 1024, threads, [&](int, Chunk part) {
    for (int i = part.begin; i < part.end; ++i) {
      const Run& r = runs[static_cast<std::size_t>(i)];
      const Curve& c = ss.curves[static_cast<std::size_t>(r.curve)];
      HiddenSegment& h = out[static_cast<std::size_t>(i)];
      h = HiddenSegment{Point2{exact_x(r.lo), exact_y(r.lo)}, Point2{exact_x(r.hi), exact_y(r.hi)}, c.kind,
                        std::vector<int>(c.faces.begin(), c.faces.end())};
      for (Point2* p : {&h.from, &h.to}) {
        unscale(p->x, ss.scale_exp);
        unscale(p->y, ss.scale_exp);
      }
    }
  });
  parallel_sort(out.begin(), out.end(), [](const HiddenSegment& a, const HiddenSegment& b) {
    if (!(a.from == b.from)) return a.from < b.from;
    return a.to < b.to;
  }, threads);
  return out;
}

}  // namespace
VISMAP_KERNEL_END

void add_hidden_lines(const Scene& scene, const View& view, const Options& options, VisibilityMap& map) {
  PhaseClock clock;
  const int threads = thread_count(options.threads, scene.faces.size());
  // Every facet and edge piece, none culled: back faces hide too, and their edges count.
  Stats scratch;
  ScreenScene ss = make_screen_scene(scene, view, options, scratch, /*latent=*/false, /*cull=*/false);
  map.stats.time("hidden_scene", clock.lap());
  add_all_intersection_lines(ss, *world_facets_of(ss), threads);
  map.stats.time("hidden_intersections", clock.lap());
  const Visibility vis(ss);
  const std::vector<Item> items = line_items(ss, map);
  map.stats.time("hidden_items", clock.lap());
  const std::vector<Run> runs = hidden_runs(ss, items, vis, threads);
  map.stats.time("hidden_runs", clock.lap());
  map.hidden = hidden_segments(ss, runs, threads);
  map.has_hidden = true;
  map.stats.count("hidden_segments", static_cast<std::int64_t>(map.hidden.size()));
  map.stats.time("hidden_lines", clock.lap());
}

}  // namespace vismap::engine
