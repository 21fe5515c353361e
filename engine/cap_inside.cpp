#include "engine/cap_inside.h"

#include <algorithm>
#include <cmath>

#include "engine/parallel.h"

namespace vismap::engine {
VISMAP_KERNEL_BEGIN

namespace {

bool apart(const CGAL::Bbox_2& a, const CGAL::Bbox_2& b) {
  return a.xmax() < b.xmin() || b.xmax() < a.xmin() || a.ymax() < b.ymin() || b.ymax() < a.ymin();
}

// The cut segments on a uniform grid over their boxes, each listed in every
// cell its box meets (a facet's box then meets a segment's only in a cell they
// share). Cells are one array, counted, then filled.
class SegmentGrid {
 public:
  explicit SegmentGrid(const std::vector<CutSegment>& cut) {
    CGAL::Bbox_2 all = cut[0].box;
    for (const CutSegment& s : cut) all += s.box;
    x0_ = all.xmin();
    y0_ = all.ymin();
    // About one segment per row and column; one cell where the box is not finite.
    const bool finite = std::isfinite(all.xmax() - all.xmin()) && std::isfinite(all.ymax() - all.ymin());
    n_ = finite ? std::clamp(static_cast<int>(std::sqrt(static_cast<double>(cut.size()))), 1, 1024) : 1;
    w_ = (all.xmax() - all.xmin()) / n_;
    h_ = (all.ymax() - all.ymin()) / n_;
    start_.assign(static_cast<std::size_t>(n_) * n_ + 1, 0);
    for (const CutSegment& s : cut) for_cells(s.box, [&](std::size_t c) { ++start_[c + 1]; });
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    members_.resize(start_.back());
    for (std::size_t i = 0; i < cut.size(); ++i)
      for_cells(cut[i].box, [&](std::size_t c) { members_[fill[c]++] = static_cast<int>(i); });
  }

  // The segments listed in the cells box b meets (a segment once per cell).
  template <class F>
  void for_each_near(const CGAL::Bbox_2& b, F&& f) const {
    for_cells(b, [&](std::size_t c) {
      for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) f(members_[k]);
    });
  }
  // The segments listed in the cells from box b's to the grid's right end, in b's rows.
  template <class F>
  void for_each_rightwards(const CGAL::Bbox_2& b, F&& f) const {
    for_each_near(CGAL::Bbox_2(b.xmin(), b.ymin(), HUGE_VAL, b.ymax()), f);
  }

 private:
  // Cell of a coordinate: monotone in it, clamped to the grid.
  static int cell(double v, double origin, double size, int n) {
    const double t = size > 0 ? std::floor((v - origin) / size) : 0;
    if (!(t >= 0)) return 0;
    return t < n ? static_cast<int>(t) : n - 1;
  }
  template <class F>
  void for_cells(const CGAL::Bbox_2& b, F&& f) const {
    const int c0 = cell(b.xmin(), x0_, w_, n_), c1 = cell(b.xmax(), x0_, w_, n_);
    const int r0 = cell(b.ymin(), y0_, h_, n_), r1 = cell(b.ymax(), y0_, h_, n_);
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c) f(static_cast<std::size_t>(r) * n_ + c);
  }

  double x0_ = 0, y0_ = 0, w_ = 0, h_ = 0;
  int n_ = 1;
  std::vector<std::size_t> start_;
  std::vector<int> members_;
};

// Whether the ray from p to the right crosses segment s (p on no segment): an
// end strictly above p's line and one not, crossing right of p. (The half-open
// rule counts a crossing through a shared end once.)
bool crosses_rightwards(const CutSegment& s, const P2& p, const CGAL::Bbox_2& pbox) {
  if (s.box.ymax() < pbox.ymin() || pbox.ymax() < s.box.ymin()) return false;   // (both ends below or above)
  if (s.box.xmax() < pbox.xmin()) return false;                                  // (wholly to the left)
  const bool a_above = CGAL::compare_y(s.a, p) == CGAL::LARGER, b_above = CGAL::compare_y(s.b, p) == CGAL::LARGER;
  if (a_above == b_above) return false;
  if (pbox.xmax() < s.box.xmin()) return true;   // (wholly to the right)
  const P2& lo = a_above ? s.b : s.a;
  const P2& hi = a_above ? s.a : s.b;
  return CGAL::orientation(lo, hi, p) == CGAL::LEFT_TURN;
}

}  // namespace

std::vector<std::int8_t> cap_sides(const ClosedComponents& cc, const std::vector<CutSegment>& cut,
                                   const std::vector<char>& candidate, const std::vector<CGAL::Bbox_2>& box,
                                   const std::vector<const P2*>& point, int threads) {
  const std::size_t n = candidate.size();
  std::vector<std::int8_t> side(n, 0);
  if (cut.empty()) return side;
  // Each component's cut box: a facet's box not within it reaches outside the cap
  // (so is not inside it).
  std::vector<CGAL::Bbox_2> cap_box(n);
  std::vector<char> has_cut(n, 0);
  for (const CutSegment& s : cut) {
    const auto c = static_cast<std::size_t>(s.component);
    cap_box[c] = has_cut[c] ? cap_box[c] + s.box : s.box;
    has_cut[c] = 1;
  }
  auto within = [](const CGAL::Bbox_2& a, const CGAL::Bbox_2& b) {
    return b.xmin() < a.xmin() && a.xmax() < b.xmax() && b.ymin() < a.ymin() && a.ymax() < b.ymax();
  };
  const SegmentGrid grid(cut);
  // Chunks of facets side by side, each with its own marks. Facets come in
  // screen order, so a facet mostly lies near the last one's point: where the
  // box of both meets no segment of their component, the facet meets none, and
  // no segment parts its point from the last one, whose parity it inherits
  // instead of casting a ray.
  parallel_chunks(static_cast<int>(n), 4096, threads, [&](int, Chunk r) {
    std::vector<std::size_t> seen(cut.size(), 0);   // (per segment: the last facet that looked at it, + 1)
    int last_c = -1;                                 // (the last point's component, box and parity)
    CGAL::Bbox_2 last_box;
    bool last_odd = false;
    auto meets_any = [&](int c, const CGAL::Bbox_2& b) {
      bool meets = false;
      grid.for_each_near(b, [&](int i) {
        const CutSegment& s = cut[static_cast<std::size_t>(i)];
        meets |= s.component == c && !apart(s.box, b);
      });
      return meets;
    };
    auto ray_parity = [&](int c, const P2& p, const CGAL::Bbox_2& pbox, std::size_t f) {
      bool odd = false;
      grid.for_each_rightwards(pbox, [&](int i) {
        const CutSegment& s = cut[static_cast<std::size_t>(i)];
        if (s.component != c || seen[static_cast<std::size_t>(i)] == f + 1) return;
        seen[static_cast<std::size_t>(i)] = f + 1;
        odd ^= crosses_rightwards(s, p, pbox);
      });
      return odd;
    };
    for (auto f = static_cast<std::size_t>(r.begin); f < static_cast<std::size_t>(r.end); ++f) {
      const int c = cc.component[f];
      if (!candidate[f] || !has_cut[static_cast<std::size_t>(c)]) continue;
      const P2& p = *point[f];
      const CGAL::Bbox_2 pbox = p.bbox();
      bool odd;
      if (c == last_c && !meets_any(c, last_box + box[f] + pbox)) {
        odd = last_odd;
      } else {
        if (meets_any(c, box[f])) continue;
        // Apart from every segment of its component, the image lies in one of
        // the regions they bound: inside a cap if its point is, else outside them all.
        odd = ray_parity(c, p, pbox, f);
      }
      last_c = c;
      last_box = pbox;
      last_odd = odd;
      if (!odd) side[f] = -1;
      else if (within(box[f], cap_box[static_cast<std::size_t>(c)])) side[f] = 1;
    }
  });
  return side;
}

VISMAP_KERNEL_END
}  // namespace vismap::engine
