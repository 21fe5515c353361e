// Franklin's variable grid (steps 2-9, 11), exact. Internal to the engine.
#pragma once
#include <deque>
#include <vector>

#include "engine/embedded_stars.h"
#include "engine/screen_scene.h"

namespace vismap::engine {
VISMAP_KERNEL_BEGIN

struct Cell {
  int blocker = -1;             // step 3a: closest facet covering the whole cell
  std::vector<int> facets;      // step 3b: facets meeting the cell, not behind the blocker
  std::vector<int> curves;      // step 3c: curves meeting the cell, not behind the blocker
};

// One axis of the grid: its cells' boundaries (exact doubles, strictly
// increasing), and a table of uniform bins that finds the cell of a coordinate
// in a step or two where cells are of similar size, by binary search where they
// are not.
class Axis {
 public:
  Axis() = default;
  explicit Axis(std::vector<double> bounds);
  double operator[](int i) const { return bounds_[static_cast<std::size_t>(i)]; }
  int cells() const { return static_cast<int>(bounds_.size()) - 1; }
  // The halving steps a lookup takes, on average over the cells.
  double steps_per_cell() const { return steps_ / cells(); }
  // The cell holding v: the last boundary <= v (clamped to the first and last cell).
  // (Inline: the grid's steps ask it tens of millions of times on 10^6 faces.)
  int index(double v) const {
    const double t = (v - lo_) * bins_per_unit_;
    const int k = t > 0 ? (t < bins_ ? static_cast<int>(t) : bins_ - 1) : 0;   // (NaN: 0)
    // The cell is among first_[k] .. first_[k + 1] (unless rounding put v in a
    // neighbouring bin: the steps below then correct it).
    // (Halving without a branch on the comparison: in a crowded bin, a close-up's
    // many small cells, the searches' outcomes are as good as random.)
    const int* first = first_.data() + k;
    const double* b = bounds_.data();
    int i = first[0];
    for (int n = first[1] - i + 1; n > 1;) {
      const int half = n / 2;
      i = b[i + half] <= v ? i + half : i;
      n -= half;
    }
    while (i > 0 && v < b[i]) --i;
    while (i < last_ && v >= b[i + 1]) ++i;
    return i;
  }

 private:
  double spread_over(int j);
  std::vector<double> bounds_;
  std::vector<int> first_;      // first_[k]: the cell holding the start of bin k
  double lo_ = 0, bins_per_unit_ = 0, steps_ = 0;
  int bins_ = 0, last_ = -1;    // (first_.size() - 1, cells() - 1)
};

// The cells a box reaches: columns x0 .. x1, rows y0 .. y1.
struct CellRange {
  int x0, x1, y0, y1;
};

struct Grid {
  int B = 1;                    // cells per side asked for (an axis may have fewer)
  Axis X, Y;                    // cell boundaries
  std::vector<Cell> cells;      // row-major: cells[iy * X.cells() + ix]
  std::vector<CellRange> facet_range;   // per facet, its box's cells (set by step 5, read by the pair search)
  std::vector<char> latent_near;        // per latent curve: its box reaches a cell a drawn curve's box reaches
                                        // (set by step 5 where it looks only there; empty: not known)
  // The boxes of runs of kRun consecutive latent curves, and of the occluding
  // facets among runs of kRun facets (empty: none), by run. Both are in screen
  // order, so a run lies close together: where a lines-only drawing looks only
  // at some cells, step 5 passes over every run whose box reaches none of them.
  // (Set by make_grid, which takes the grid's box from them.)
  static constexpr int kRun = 64;
  std::vector<CGAL::Bbox_2> latent_runs, occluder_runs;
  Cell& at(int ix, int iy) { return cells[static_cast<std::size_t>(iy) * X.cells() + ix]; }
  const Cell& at(int ix, int iy) const { return cells[static_cast<std::size_t>(iy) * X.cells() + ix]; }
};

// A piece of a curve between consecutive cut points, classified at its midpoint.
struct VisiblePiece {
  P2 a, b;                      // along the curve's direction s -> t
  int curve = -1;
  int left = -1, right = -1;    // nearest face just left / right of the piece (-1: none)
  bool visible = false;         // an edge piece or intersection line, not hidden at its interior
                                // (drawn or not: a visible smooth seam covers lines behind it)
  bool boundary = false;        // this curve bounds a region here
};

// Facet and curve geometry the grid's steps use, shared with hidden_lines.cpp.
// +1 for counter-clockwise facets, -1 for clockwise: the side their interior is on.
inline int turn(const Facet& f) { return f.facing == Facing::Front ? 1 : -1; }
// Screen point p strictly inside the projection of the convex facet f.
bool strictly_inside(const Facet& f, const P2& p);
// sign(depth of p - depth of f's plane under p). Where p is input vertex id (or
// -1) and world the input's vertices, an exact zero (a vertex of a coplanar
// neighbour: common on flat parts of a mesh) is found without rationals.
CGAL::Sign depth_above(const P3& p, const Facet& f, const std::vector<Vec3>* world = nullptr, long id = -1);
// Where facets A and B cross in 3D strictly inside both projections, as a screen
// segment p-q; false when they do not, or only along an edge of either.
bool intersection_segment(const Facet& A, const Facet& B, const std::vector<Vec3>* world, P2& p, P2& q);

// The curve of the crossing p-q of facets A and B (fa, fb), its depths A's.
// Where A or B may cross at a diagonal (Facet::may_cross_at_diagonal), the line
// may lie on facet edges, and predicates on its ends be exactly degenerate:
// their exact values are computed here, before the threads share them. (A lazy number's
// interval narrows once its exact value is known, so which thread computed it
// first would change which later predicates the filter settles, and the counts
// in the JSON must not depend on the thread count.) Elsewhere its ends are
// frozen copies (exact_kernel.h), whose intervals do not narrow.
Curve crossing_curve(const Facet& A, const Facet& B, int fa, int fb, const P2& p, const P2& q, std::deque<P3>& ends);
// Where segments a-b and c-d cross (they do, properly): one lazy node, whose
// interval is the common part of both segments' (a crossing on an axis-parallel
// segment gets that segment's exact coordinate) and whose exact value is made
// on integers, without a gcd at every step.
P2 crossing_point(const P2& a, const P2& b, const P2& c, const P2& d);
// Neighbours on a mesh that cannot pierce each other, told by their corners
// alone: an edge in common, or one corner in common whose star lies flat on
// the screen (`stars`). (Most pairs the searches meet on a mesh.)
bool neighbours_apart(const Facet& A, const Facet& B, const EmbeddedStars& stars);
// Facets that cannot pierce each other, told with no arithmetic on their
// points: their depth ranges apart, or neighbours apart by their corners.
// (The pair searches' first test.)
inline bool cannot_pierce(const Facet& A, const Facet& B, const EmbeddedStars& stars) {
  return A.zhi < B.zlo || B.zhi < A.zlo || neighbours_apart(A, B, stars);
}
// sign(depth of C - depth of D) at point p of the common screen line of curves C
// and D, parametrised along x (along y if the line is vertical).
CGAL::Sign depth_gap(const Curve& C, const Curve& D, const P2& p, bool along_x);
// The screen point x where collinear curves C and D have equal depth, strictly
// between lo and hi on their line; false if their depth order does not change there.
// (x and plane_crossing's point are cut into curves that threads share: frozen
// copies, exact_kernel.h, whose intervals do not narrow once exact.)
bool depth_crossing(const Curve& C, const Curve& D, const P2& lo, const P2& hi, P2& x);
// Where curve C crosses facet F's depth plane (its ends on either side of it).
P2 plane_crossing(const Curve& C, const Facet& F);

Grid make_grid(ScreenScene& ss, double c, int threads, Stats& stats);       // steps 2-4
void bucket_facets(Grid& g, ScreenScene& ss, bool regions, int threads, Stats& stats);         // step 5
void prune_facets(Grid& g, const ScreenScene& ss, int threads, Stats& stats);                  // step 6
void add_intersection_lines(const Grid& g, ScreenScene& ss, int threads, Stats& stats);   // faces piercing each other
void bucket_curves(Grid& g, ScreenScene& ss, bool regions, int threads, Stats& stats);   // step 7
// Step 8's cut points per curve, and which curves the map needs (all of them,
// unless only the drawn lines are wanted).
// Where each curve is cut; most curves of a mesh are cut nowhere, so only those
// that are have a list (a list per curve was 24 bytes each, a million of them).
struct Cuts {
  std::vector<char> needed;
  std::vector<P2>& at(int c) {   // (made empty on first use)
    std::uint32_t& k = list_of[static_cast<std::size_t>(c)];
    if (k == kNone) { k = static_cast<std::uint32_t>(lists.size()); lists.emplace_back(); }
    return lists[k];
  }
  std::vector<P2>* find(int c) {   // (nullptr: none)
    const std::uint32_t k = list_of[static_cast<std::size_t>(c)];
    return k == kNone ? nullptr : &lists[k];
  }
  static constexpr std::uint32_t kNone = ~0u;
  std::vector<std::uint32_t> list_of;   // per curve: its list in `lists`, or kNone
  std::vector<std::vector<P2>> lists;
};
Cuts cut_curves(Grid& g, const ScreenScene& ss, bool regions, int threads, Stats& stats);        // step 8
// Steps 9 and 11's pieces in curve order, in chunks (one list per chunk of curves
// the threads classified: joined, they would be one more copy at the peak).
using PieceChunks = std::vector<std::vector<VisiblePiece>>;
PieceChunks classify_pieces(const Grid& g, const ScreenScene& ss, Cuts& cuts, int threads, Stats& stats);  // steps 9, 11

VISMAP_KERNEL_END
}  // namespace vismap::engine
