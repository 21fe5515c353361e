// Newell's fragments -> map pieces, exact. A uniform bucket grid over bounding
// boxes (doubles that contain the exact values) only proposes candidates; every
// decision is an exact predicate.
#include "engine/newell_overlay.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <unordered_map>

#include "engine/franklin_grid.h"
#include "engine/midpoint_probe.h"
#include "engine/newell_geometry.h"
#include "engine/overlap_cuts.h"

namespace vismap::engine {
namespace {

using namespace newell;

// A (constructed) point's interval made bounded: a crossing of two nearly
// parallel lines can carry an unbounded one until its exact value is asked
// for, which narrows it.
void bound(const P2& p) {
  const auto b = CGAL::approx(p).bbox();
  if (!std::isfinite(b.xmin()) || !std::isfinite(b.xmax()) || !std::isfinite(b.ymin()) || !std::isfinite(b.ymax()))
    CGAL::exact(p);
}

// Items by bounding box in a uniform grid of buckets. An item is listed in every
// bucket its box meets; a pair (or an item and a query box) is reported only by
// the bucket holding the lower-left corner of their boxes' common part, so once.
// (That bucket's column is the larger of the two boxes' first columns, the cell
// index being monotone: each item's first column and row are kept, so that the
// test divides nothing.)
class BoxGrid {
 public:
  explicit BoxGrid(const std::vector<CGAL::Bbox_2>& boxes) : boxes_(boxes) {
    if (boxes.empty()) return;
    CGAL::Bbox_2 all = boxes[0];
    double sizes = 0;
    for (const auto& b : boxes) {
      all += b;
      sizes += std::max(b.xmax() - b.xmin(), b.ymax() - b.ymin());
    }
    const double n = static_cast<double>(boxes.size());
    const double extent = std::max(all.xmax() - all.xmin(), all.ymax() - all.ymin());
    double b = std::sqrt(n);
    if (sizes > 0 && extent > 0) b = std::min(b, 2 * extent * n / sizes);   // cells about half an item wide
    B_ = static_cast<int>(std::clamp(b, 1.0, 1024.0));
    x0_ = all.xmin();
    y0_ = all.ymin();
    w_ = (all.xmax() - x0_) / B_;
    h_ = (all.ymax() - y0_) / B_;
    if (!(w_ > 0)) w_ = 1;
    if (!(h_ > 0)) h_ = 1;
    // The buckets as one array (each bucket's items from start_[c]): counted,
    // then filled, in item order. (A vector per bucket was an allocation each,
    // five grids per view.)
    first_.resize(boxes.size());
    for (int i = 0; i < static_cast<int>(boxes.size()); ++i) first_[i] = {cx(boxes[i].xmin()), cy(boxes[i].ymin())};
    auto each_cell = [&](int i, auto&& visit) {
      for (int iy = first_[i].y; iy <= cy(boxes[i].ymax()); ++iy)
        for (int ix = first_[i].x; ix <= cx(boxes[i].xmax()); ++ix) visit(cell(ix, iy));
    };
    start_.assign(static_cast<std::size_t>(B_) * B_ + 1, 0);
    for (int i = 0; i < static_cast<int>(boxes.size()); ++i) each_cell(i, [&](int c) { ++start_[c + 1]; });
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    items_.resize(start_.back());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (int i = 0; i < static_cast<int>(boxes.size()); ++i) each_cell(i, [&](int c) { items_[fill[c]++] = i; });
  }

  // f(i, j), i < j, for every two items whose boxes overlap.
  template <class F>
  void pairs(F&& f) const {
    for (int c = 0; c + 1 < static_cast<int>(start_.size()); ++c) {
      const int* l = items_.data() + start_[c];
      const std::size_t n = start_[c + 1] - start_[c];
      for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = a + 1; b < n; ++b) {
          const auto &p = boxes_[l[a]], &q = boxes_[l[b]];
          if (!CGAL::do_overlap(p, q)) continue;
          const Corner &fp = first_[l[a]], &fq = first_[l[b]];
          if (cell(std::max(fp.x, fq.x), std::max(fp.y, fq.y)) != c) continue;
          f(std::min(l[a], l[b]), std::max(l[a], l[b]));
        }
    }
  }

  // Whether f(i) holds for an item whose box contains q, asked in the order
  // `overlapping` reports them, until one does. Each such box holds q's lower
  // left corner, so it is listed in that corner's cell: one cell holds them all, once.
  template <class F>
  bool any_containing(const CGAL::Bbox_2& q, F&& f) const {
    if (items_.empty()) return false;
    const int c = cell(cx(q.xmin()), cy(q.ymin()));
    for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) {
      const int i = items_[k];
      const CGAL::Bbox_2& b = boxes_[i];
      if (b.xmin() <= q.xmin() && q.xmax() <= b.xmax() && b.ymin() <= q.ymin() && q.ymax() <= b.ymax() && f(i))
        return true;
    }
    return false;
  }

  // f(i) for every item whose box overlaps q.
  template <class F>
  void overlapping(const CGAL::Bbox_2& q, F&& f) const {
    if (items_.empty()) return;
    const Corner fq{cx(q.xmin()), cy(q.ymin())};
    for (int iy = fq.y; iy <= cy(q.ymax()); ++iy)
      for (int ix = fq.x; ix <= cx(q.xmax()); ++ix) {
        const int c = cell(ix, iy);
        for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) {
          const int i = items_[k];
          if (!CGAL::do_overlap(boxes_[i], q)) continue;
          if (cell(std::max(first_[i].x, fq.x), std::max(first_[i].y, fq.y)) != c) continue;
          f(i);
        }
      }
  }

 private:
  // Monotone in x, so a point of a box falls in the box's range of cells.
  int cx(double x) const { return index((x - x0_) / w_); }
  int cy(double y) const { return index((y - y0_) / h_); }
  int index(double u) const {
    if (!(u >= 0)) return 0;   // below the grid (or NaN)
    return u >= B_ ? B_ - 1 : static_cast<int>(u);
  }
  int cell(int ix, int iy) const { return iy * B_ + ix; }

  struct Corner {
    int x, y;   // column and row
  };
  const std::vector<CGAL::Bbox_2>& boxes_;
  int B_ = 1;
  double x0_ = 0, y0_ = 0, w_ = 1, h_ = 1;
  std::vector<std::size_t> start_;   // bucket c's items are items_[start_[c] .. start_[c + 1])
  std::vector<int> items_;
  std::vector<Corner> first_;   // each item's first column and row
};

// ---- cutting curves ----------------------------------------------------------------

struct Cutter {
  const ScreenScene& ss;
  CutPoints& cuts;
  std::vector<std::pair<int, int>> overlaps{};   // collinear curves sharing more than a point
  std::int64_t pairs = 0, crossings = 0;

  // (x: a number equal to p's x whose exact value is cheap, where known.)
  void cut(int c, const P2& p, const FT* x = nullptr) {
    cuts.at[c].push_back(p);
    if (x) cuts.known_x.emplace_back(p.id(), x);
  }

  // p lies on C's line strictly between its end points.
  static bool inside(const Curve& C, const P2& p) {
    return between_on_line(C.s->xy(), p, C.t->xy(), /*strictly=*/true);
  }

  void pair(int ci, int di) {
    const Curve &C = ss.curves[ci], &D = ss.curves[di];
    ++pairs;
    const P2 c0 = C.s->xy(), c1 = C.t->xy(), d0 = D.s->xy(), d1 = D.t->xy();
    // End points that are one input vertex need no predicate to meet there.
    auto same = [](long a, long b) { return a >= 0 && a == b; };
    if (same(C.vs, D.vs) || same(C.vs, D.vt) || same(C.vt, D.vs) || same(C.vt, D.vt)) {
      // From the common point o they go to c and d: only if they leave o in the
      // same direction does one continue past the other's end. Their depths agree
      // at o and are affine along the common part, so they cannot cross in it.
      const bool at_cs = same(C.vs, D.vs) || same(C.vs, D.vt), at_ds = same(C.vs, D.vs) || same(C.vt, D.vs);
      const P2 o = at_cs ? c0 : c1, c = at_cs ? c1 : c0;
      const P2 d = at_ds ? d1 : d0;
      if (CGAL::orientation(o, c, d) != CGAL::COLLINEAR || !CGAL::is_positive((c - o) * (d - o))) return;
      overlaps.emplace_back(ci, di);
      if (inside(C, d)) cut(ci, d, at_ds ? &D.t->x : &D.s->x);
      else if (inside(D, c)) cut(di, c, at_cs ? &C.t->x : &C.s->x);
      return;
    }
    const auto o1 = CGAL::orientation(c0, c1, d0), o2 = CGAL::orientation(c0, c1, d1);
    if (o1 == o2 && o1 != CGAL::COLLINEAR) return;   // D wholly on one side of C's line
    if (o1 == CGAL::COLLINEAR && o2 == CGAL::COLLINEAR) { collinear(ci, di); return; }
    const auto o3 = CGAL::orientation(d0, d1, c0), o4 = CGAL::orientation(d0, d1, c1);
    if (o3 == o4 && o3 != CGAL::COLLINEAR) return;
    if (o1 != CGAL::COLLINEAR && o2 != CGAL::COLLINEAR && o3 != CGAL::COLLINEAR && o4 != CGAL::COLLINEAR) {
      // A proper crossing (made as Franklin's engine makes one: franklin_grid.h).
      const P2 x = crossing_point(c0, c1, d0, d1);
      // On an upright curve, its x.
      const FT* line_x = cuts.upright[ci] ? &C.s->x : cuts.upright[di] ? &D.s->x : nullptr;
      cut(ci, x, line_x);
      cut(di, x);
      ++crossings;
      return;
    }
    // One ends on the other.
    if (o1 == CGAL::COLLINEAR && inside(C, d0)) cut(ci, d0, &D.s->x);
    if (o2 == CGAL::COLLINEAR && inside(C, d1)) cut(ci, d1, &D.t->x);
    if (o3 == CGAL::COLLINEAR && inside(D, c0)) cut(di, c0, &C.s->x);
    if (o4 == CGAL::COLLINEAR && inside(D, c1)) cut(di, c1, &C.t->x);
  }

  // On one line: each is cut at the other's end points inside it and, where both
  // are present, where their depths cross (so one of them is first on each piece).
  void collinear(int ci, int di) {
    const Curve &C = ss.curves[ci], &D = ss.curves[di];
    const P2 c0 = C.s->xy(), c1 = C.t->xy(), d0 = D.s->xy(), d1 = D.t->xy();
    auto less = [](const P2& a, const P2& b) { return compare_xy_exactly(a, b) == CGAL::SMALLER; };
    const P2 clo = std::min(c0, c1, less), chi = std::max(c0, c1, less);
    const P2 dlo = std::min(d0, d1, less), dhi = std::max(d0, d1, less);
    // (Lexicographic order is the order along the line.)
    const P2 lo = std::max(clo, dlo, less), hi = std::min(chi, dhi, less);
    if (!less(lo, hi)) return;   // they meet in a point at most
    overlaps.emplace_back(ci, di);
    if (inside(C, d0)) cut(ci, d0, &D.s->x);
    if (inside(C, d1)) cut(ci, d1, &D.t->x);
    if (inside(D, c0)) cut(di, c0, &C.s->x);
    if (inside(D, c1)) cut(di, c1, &C.t->x);
    const FT flo = depth_on(C, lo) - depth_on(D, lo), fhi = depth_on(C, hi) - depth_on(D, hi);
    if (CGAL::sign(flo) * CGAL::sign(fhi) < 0) {
      const P2 x = lo + (flo / (flo - fhi)) * (hi - lo);
      cut(ci, x);
      cut(di, x);
      ++crossings;
    }
  }
};

// ---- painting ------------------------------------------------------------------------

// The curve being painted: its ends, and which fragment sides lie on its line
// (asked only for sides the intervals cannot tell from the midpoint: those are
// nearly always its own facets' edges, and the split lines along an
// intersection line). A side on the facet edge that holds the curve (the
// fragment's Fragment::edge, the curve's sharer_edge) is told by index; any
// other once per side, on exact leaves.
struct CurveLine {
  const Curve& cv;
  std::unordered_map<std::uint64_t, bool> on_line;
  bool side_on_line(const Fragment& X, int frag, std::size_t k, const P3& p, const P3& q) {
    if (X.edge[k] >= 0)
      for (std::size_t i = 0; i < cv.sharers.size(); ++i)
        if (cv.sharers[i] == X.facet && cv.sharer_edge[i] == X.edge[k]) return true;
    auto [it, fresh] = on_line.try_emplace((static_cast<std::uint64_t>(frag) << 24) | k, false);
    if (fresh) it->second = orient(p, q, *cv.s) == CGAL::ZERO && orient(p, q, *cv.t) == CGAL::ZERO;
    return it->second;
  }
};

// Orientation of (p, q, m) for X's side k, p -> q: with the ends of the facet
// edge that holds it (Fragment::edge), whose input vertices span its line.
CGAL::Sign side_orientation(const Fragment& X, std::size_t k, const P3& p, const P3& q, Probe& m) {
  const int j = X.edge[k];
  if (j < 0) return orientation(p, q, -1, -1, m);
  const Facet& F = m.screen->facet(static_cast<std::size_t>(X.facet));
  return orientation_on_spanned_line(p, q, F.id[static_cast<std::size_t>(j)],
                                     F.id[(static_cast<std::size_t>(j) + 1) % F.id.size()], m);
}

// Whether fragment X (counter-clockwise, number frag) contains the points just
// left and just right of m on the curve: m + e n + e^2 d and m - e n + e^2 d for
// an infinitesimal e > 0, d = t - s the curve's direction and n its left normal.
// The e^2 term settles a fragment side through m across the curve (a split
// line, which is no curve). Called with the rounding upward (exact::UpwardRounding).
bool covers(const Fragment& X, int frag, Probe& m, CurveLine& line, bool& left, bool& right) {
  assert(exact::rounding_upward);
  left = right = true;
  const std::size_t n = X.v.size();
  for (std::size_t k = 0; k < n; ++k) {
    const P3 &p = X.v[k], &q = X.v[(k + 1) % n];
    const Interval v = (q.x.approx() - p.x.approx()) * (m.iy - p.y.approx()) -
                       (q.y.approx() - p.y.approx()) * (m.ix - p.x.approx());
    const auto told = exact::sign_of(v);   // (an interval of exactly 0 too)
    const CGAL::Sign o = told                                  ? *told
                         : line.side_on_line(X, frag, k, p, q) ? CGAL::ZERO
                                                               : side_orientation(X, k, p, q, m);
    if (o == CGAL::POSITIVE) continue;
    if (o == CGAL::NEGATIVE) return left = right = false;
    // m on this side's line. Its inward normal is (q - p) turned left: against n
    // it gives (q - p).d, against d the cross product (q - p) x d.
    const auto across = dot_sign(p, q, *line.cv.s, *line.cv.t);
    if (across > 0) right = false;
    else if (across < 0) left = false;
    else if (cross_sign(p, q, *line.cv.s, *line.cv.t) <= 0) return left = right = false;
    if (!left && !right) return false;
  }
  return true;
}

struct Cover {
  int frag;          // position in the drawing order
  int face;
  bool left, right;
};

// Fragment T, covering both sides of m, hides the curve there by the spec's rule
// on its own: another face, and nearer at m (or as near, with a lower index).
bool in_front(const ScreenScene& ss, const Curve& cv, const Fragment& T, Probe& m) {
  if (std::binary_search(cv.faces.begin(), cv.faces.end(), T.face)) return false;
  const CGAL::Sign order = depth_against_curve(ss.facets[T.facet], m);
  return order == CGAL::NEGATIVE || (order == CGAL::ZERO && T.face < cv.order_face);
}

// Whether a fragment of a face that is not one of cv's covers both sides of m and
// is painted over the curve there. The curve's own fragment is the last-drawn
// fragment of its facets beside m: a fragment over the same side drawn after it
// is in front of it, one drawn before is behind (the order guarantees it; the
// exact depth at m checks it, and settles equal depth by the spec's face-index
// rule). Where the curve has no fragment of its own (an edge of edge-on faces
// only), or for a fragment over the other side, the depths at m decide.
bool painted_over(const ScreenScene& ss, const std::vector<Fragment>& order, const Curve& cv, Probe& m,
                  const std::vector<Cover>& cov) {
  int own = -1;
  for (int i = 0; i < static_cast<int>(cov.size()); ++i) {
    const int facet = order[cov[i].frag].facet;
    if (std::find(cv.sharers.begin(), cv.sharers.end(), facet) == cv.sharers.end()) continue;
    if (own < 0 || cov[i].frag > cov[own].frag) own = i;
  }
  const bool own_left = own >= 0 && cov[own].left;
  for (int i = 0; i < static_cast<int>(cov.size()); ++i) {
    const int g = cov[i].face;
    if (std::binary_search(cv.faces.begin(), cv.faces.end(), g)) continue;
    // Face g covers both sides: this fragment alone, or with another of g's that
    // meets it at m (the same depth there); a fold's other layer does not count.
    bool l = cov[i].left, r = cov[i].right;
    const Facet& fi = ss.facets[order[cov[i].frag].facet];
    for (const Cover& c : cov)
      if (!(l && r) && c.face == g && (c.left != l || c.right != r) &&
          depth_order(ss.facets[order[c.frag].facet], fi, m) == CGAL::ZERO) {
        l |= c.left;
        r |= c.right;
      }
    if (!(l && r)) continue;
    const CGAL::Sign cmp = depth_against_curve(fi, m);
    if (cmp == CGAL::ZERO) {
      if (g < cv.order_face) return true;
      continue;
    }
    if (own >= 0 && (own_left ? cov[i].left : cov[i].right)) {
      const bool after = cov[i].frag > cov[own].frag;
      if (after != (cmp == CGAL::NEGATIVE))
        throw std::logic_error("newell: the drawing order contradicts the depths (engine bug)");
      if (after) return true;
    } else if (cmp == CGAL::NEGATIVE) {
      return true;
    }
  }
  return false;
}

}  // namespace

void add_piercing_lines(ScreenScene& ss, Stats& stats) {
  std::vector<int> occ;
  std::vector<CGAL::Bbox_2> boxes;
  for (int fi = 0; fi < static_cast<int>(ss.facets.size()); ++fi)
    if (ss.facets[fi].occluder) { occ.push_back(fi); boxes.push_back(ss.facets[fi].box); }
  std::int64_t tested = 0, found = 0;
  std::vector<Curve> lines;
  std::deque<P3>& line_ends = ss.ends.emplace_back();
  const EmbeddedStars stars(ss, 1, !occluders_all_in_solids(ss));
  BoxGrid(boxes).pairs([&](int i, int j) {
    const int fa = occ[i], fb = occ[j];
    const Facet &A = ss.facets[fa], &B = ss.facets[fb];
    // (Two facets of one solid that does not meet itself never pierce each other.)
    if (solid_of(ss, fa) >= 0 && solid_of(ss, fa) == solid_of(ss, fb)) return;
    // (Franklin's test of a pair, franklin_grid.h: neighbours on a mesh are told
    // by their shared edge or corner, or on doubles in the world.)
    if (A.face == B.face || cannot_pierce(A, B, stars)) return;
    ++tested;
    P2 p, q;
    if (!intersection_segment(A, B, ss.world, p, q)) return;
    ++found;
    lines.push_back(crossing_curve(A, B, fa, fb, p, q, line_ends));
  });
  for (auto& c : lines) ss.curves.push_back(std::move(c));
  stats.count("facet_pairs_tested", tested);
  stats.count("intersection_lines", found);
}

void drop_painted_over(ScreenScene& ss, const std::vector<Fragment>& order, Stats& stats) {
  std::vector<CGAL::Bbox_2> boxes;
  boxes.reserve(order.size());
  for (const Fragment& f : order) boxes.push_back(f.box);
  const BoxGrid grid(boxes);
  auto covered = [&](const Curve& cv) {
    return grid.any_containing(cv.box, [&](int i) {
      const Fragment& G = order[i];
      if (std::binary_search(cv.faces.begin(), cv.faces.end(), G.face) ||
          std::find(cv.sharers.begin(), cv.sharers.end(), G.facet) != cv.sharers.end())
        return false;
      // Only a planar polygon's fragment: a line another curve shares with a fanned
      // one can pass behind the fold's front layer unhidden (it shares the face), and
      // its visibility changes where this curve crosses it (a fuzz finding).
      const Facet& F = ss.facets[G.facet];
      if (!F.planar) return false;
      for (const P3* e : {cv.s, cv.t}) {
        for (std::size_t k = 0; k < G.v.size(); ++k)
          if (orient(G.v[k], G.v[(k + 1) % G.v.size()], *e) != CGAL::POSITIVE) return false;
        if (plane_side(*e, F) != CGAL::POSITIVE) return false;   // the curve's end strictly behind G
      }
      return true;
    });
  };
  const std::size_t before = ss.curves.size();
  ss.curves.erase(std::remove_if(ss.curves.begin(), ss.curves.end(), covered), ss.curves.end());
  stats.count("curves_painted_over", static_cast<std::int64_t>(before - ss.curves.size()));
}

const FT* CutPoints::x_of(const P2& p) const {
  const auto it = std::lower_bound(known_x.begin(), known_x.end(), p.id(),
                                   [](const auto& entry, CGAL::Handle::Id_type id) { return entry.first < id; });
  return it != known_x.end() && it->first == p.id() ? it->second : nullptr;
}

CutPoints cut_at_crossings(const ScreenScene& ss, Stats& stats) {
  CutPoints cuts;
  cuts.at.resize(ss.curves.size());
  cuts.upright.resize(ss.curves.size());
  for (std::size_t ci = 0; ci < ss.curves.size(); ++ci) {
    const Curve& c = ss.curves[ci];
    const Interval sx = approx_of(c.s->x), tx = approx_of(c.t->x);
    cuts.upright[ci] = !(sx.sup() < tx.inf() || tx.sup() < sx.inf()) && CGAL::compare(c.s->x, c.t->x) == CGAL::EQUAL;
  }
  std::vector<CGAL::Bbox_2> boxes;
  boxes.reserve(ss.curves.size());
  for (const Curve& c : ss.curves) boxes.push_back(c.box);
  Cutter cutter{ss, cuts};
  BoxGrid(boxes).pairs([&](int i, int j) { cutter.pair(i, j); });
  stats.count("edge_pairs_tested", cutter.pairs);
  stats.count("intersections", cutter.crossings);

  // A line none of whose facets hides anything (an edge of faces seen edge-on)
  // can pass through another face's plane inside it with no intersection line
  // ending there (those are drawn only between occluding facets): where it
  // pierces an occluding facet, its visibility changes, so it is cut there too.
  std::vector<int> occ;
  std::vector<CGAL::Bbox_2> facet_boxes;
  for (int fi = 0; fi < static_cast<int>(ss.facets.size()); ++fi)
    if (ss.facets[fi].occluder) { occ.push_back(fi); facet_boxes.push_back(ss.facets[fi].box); }
  const BoxGrid facets(facet_boxes);
  std::int64_t piercings = 0;
  for (int ci = 0; ci < static_cast<int>(ss.curves.size()); ++ci) {
    const Curve& cv = ss.curves[ci];
    if (std::any_of(cv.sharers.begin(), cv.sharers.end(), [&](int f) { return ss.facets[f].occluder; })) continue;
    facets.overlapping(cv.box, [&](int i) {
      const Facet& G = ss.facets[occ[i]];
      if (plane_side(*cv.s, G) * plane_side(*cv.t, G) >= 0) return;   // not strictly through G's plane
      const FT hs = cv.s->z - G.depth_at(cv.s->xy()), ht = cv.t->z - G.depth_at(cv.t->xy());
      const P2 x = cv.s->xy() + (hs / (hs - ht)) * (cv.t->xy() - cv.s->xy());
      const int turn = G.facing == Facing::Front ? 1 : -1;
      for (std::size_t k = 0; k < G.v.size(); ++k)
        if (CGAL::orientation(G.v[k].xy(), G.v[(k + 1) % G.v.size()].xy(), x) * turn <= 0) return;
      cuts.at[ci].push_back(x);
      ++piercings;
    });
  }
  stats.count("piercings", piercings);
  // Last, when every curve has its own cuts: collinear curves that overlap
  // take each other's, piercings and depth crossings with a third included.
  share_overlap_cuts(ss.curves, cutter.overlaps, [&](int c) { return &cuts.at[c]; },
                     [&](int c, auto first, auto last) { cuts.at[c].insert(cuts.at[c].end(), first, last); });
  std::sort(cuts.known_x.begin(), cuts.known_x.end());
  return cuts;
}

std::vector<MapPiece> paint_pieces(const ScreenScene& ss, const std::vector<Fragment>& order, CutPoints& cuts,
                                   const std::vector<FacesList>& faces, Stats& stats) {
  std::vector<CGAL::Bbox_2> boxes;
  boxes.reserve(order.size());
  for (const Fragment& f : order) boxes.push_back(f.box);
  const BoxGrid grid(boxes);
  std::vector<MapPiece> out;
  std::vector<Cover> cov;
  std::vector<int> cand;
  std::int64_t pieces = 0, visible = 0;
  for (int ci = 0; ci < static_cast<int>(ss.curves.size()); ++ci) {
    const Curve& cv = ss.curves[ci];
    const P2 s = cv.s->xy(), t = cv.t->xy();
    CurveLine line{cv, {}};
    Probe m = probe_of(ss, cv);
    // Sort the cuts along the curve (by its dominant coordinate); a point cut
    // twice is one cut.
    std::vector<P2>& pts = cuts.at[ci];
    const bool use_x = mostly_along_x(cv);
    const auto forward = use_x ? CGAL::compare_x(s, t) : CGAL::compare_y(s, t);
    auto along = [&](const P2& a, const P2& b) {   // (a point cut twice is often one number: equal by identity)
      if (exact::same_rep(a, b)) return CGAL::EQUAL;
      return use_x ? CGAL::compare_x(a, b) : CGAL::compare_y(a, b);
    };
    std::sort(pts.begin(), pts.end(), [&](const P2& a, const P2& b) { return along(a, b) == forward; });
    // (On one line, equal along the dominant axis is the same point.)
    pts.erase(std::unique(pts.begin(), pts.end(), [&](const P2& a, const P2& b) { return along(a, b) == CGAL::EQUAL; }),
              pts.end());
    pts.insert(pts.begin(), s);
    pts.push_back(t);
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
      ++pieces;
      bound(pts[k]);
      bound(pts[k + 1]);
      {
        CGAL::Protect_FPU_rounding<true> upward;
        m.at_midpoint(pts[k], pts[k + 1]);
      }
      // The fragments near m, last drawn first: the first covering each side is
      // what is painted there. Usually one fragment covers both sides and lies
      // in front of the curve, which settles the piece (hidden, one face on both
      // sides); otherwise every fragment around m is looked at.
      cand.clear();
      const CGAL::Bbox_2 mbox(m.ix.inf(), m.iy.inf(), m.ix.sup(), m.iy.sup());
      grid.overlapping(mbox, [&](int i) { cand.push_back(i); });   // (rounding to nearest, as the grid was made)
      std::sort(cand.begin(), cand.end(), std::greater<int>());
      // Judged with the rounding upward throughout: every predicate from here is
      // exact::filtered_sign's (one switch of the FPU's mode, not one per fragment side).
      exact::UpwardRounding upward;
      cov.clear();
      int top_left = -1, top_right = -1;
      std::size_t next = 0;
      auto scan = [&](bool until_both) {
        for (; next < cand.size(); ++next) {
          const int i = cand[next];
          bool l, r;
          if (!covers(order[i], i, m, line, l, r)) continue;
          cov.push_back(Cover{i, order[i].face, l, r});
          if (l && top_left < 0) top_left = i;
          if (r && top_right < 0) top_right = i;
          if (until_both && top_left >= 0 && top_right >= 0) { ++next; return; }
        }
      };
      scan(true);
      const int left = top_left < 0 ? -1 : order[top_left].face;
      const int right = top_right < 0 ? -1 : order[top_right].face;
      // Edge pieces that are not drawn (smooth) are judged too: where lines
      // coincide on the screen, the first visible one decides, drawn or not.
      bool seen = false;
      if (!cv.faces.empty()) {
        if (top_left >= 0 && top_left == top_right && in_front(ss, cv, order[top_left], m)) {
          seen = false;
        } else {
          scan(false);
          seen = !painted_over(ss, order, cv, m, cov);
        }
      }
      const bool drawn = seen && cv.drawn;
      visible += drawn;
      if (!seen && left == right) continue;
      MapPiece mp;
      mp.a = pts[k];
      mp.b = pts[k + 1];
      mp.left = left;
      mp.right = right;
      mp.visible = seen;
      mp.drawn = drawn;
      mp.kind = cv.kind;
      mp.faces = &faces[static_cast<std::size_t>(ci)];
      mp.order_face = cv.order_face;
      mp.s = cv.s;
      mp.t = cv.t;
      mp.line = ci;
      if (cuts.upright[ci]) {
        mp.xa = mp.xb = &cv.s->x;
      } else {
        mp.xa = k == 0 ? &cv.s->x : cuts.x_of(pts[k]);
        mp.xb = k + 2 == pts.size() ? &cv.t->x : cuts.x_of(pts[k + 1]);
      }
      mp.ida = k == 0 ? cv.vs : -1;   // (the curve's own ends: its vertices where it has them)
      mp.idb = k + 2 == pts.size() ? cv.vt : -1;
      out.push_back(std::move(mp));
    }
  }
  stats.count("pieces", pieces);
  stats.count("visible_pieces", visible);
  stats.count("map_pieces", static_cast<std::int64_t>(out.size()));
  return out;
}

}  // namespace vismap::engine
