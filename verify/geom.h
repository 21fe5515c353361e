// Exact planar primitives on GMP rationals. Every predicate is a sign of an
// exact expression; nothing is rounded.
#pragma once
#include <gmpxx.h>

#include <cstdint>
#include <string>
#include <vector>

namespace vismap_check {

struct P2 {
  mpq_class x, y;
};
inline bool operator==(const P2& a, const P2& b) { return a.x == b.x && a.y == b.y; }
inline bool operator!=(const P2& a, const P2& b) { return !(a == b); }

std::string str(const P2& p);   // "(x, y)" with canonical rationals

// (a - o) x (b - o): positive when o, a, b turn counter-clockwise.
mpq_class cross(const P2& o, const P2& a, const P2& b);
// d1 x d2 for two direction vectors.
mpq_class cross_dir(const P2& d1, const P2& d2);
// Sign of cross(o, a, b), by integer arithmetic on numerators and denominators
// (no gcd: the hot predicate of the checker).
int orient(const P2& o, const P2& a, const P2& b);

// q on the closed segment [a, b] (a == b allowed: then q == a).
bool on_segment(const P2& q, const P2& a, const P2& b);

// Twice the signed area (shoelace) of a closed ring given without its closing vertex.
mpq_class area2(const std::vector<P2>& ring);

struct Box {
  mpq_class xmin, xmax, ymin, ymax;
  bool contains(const P2& q) const { return xmin <= q.x && q.x <= xmax && ymin <= q.y && q.y <= ymax; }
  bool meets(const Box& b) const {
    return xmin <= b.xmax && b.xmin <= xmax && ymin <= b.ymax && b.ymin <= ymax;
  }
};
Box box_of(const std::vector<P2>& pts);   // pts non-empty
Box box_of(const P2& a, const P2& b);

// Buckets of boxes on an exact uniform grid, so that a point query looks only
// at the boxes near it. Cells are found with exact floors, never rounding.
class BoxGrid {
 public:
  void build(const std::vector<Box>& boxes);
  // Indices of the boxes that may hold q (a superset: test the box itself).
  const std::vector<std::uint32_t>& near(const P2& q) const;

 private:
  int cell(const mpq_class& v, const mpq_class& lo, const mpq_class& size) const;
  int n_ = 0;
  mpq_class x0_, y0_, cw_, ch_;
  std::vector<std::vector<std::uint32_t>> cells_;   // n_ * n_, row-major by y
  std::vector<std::uint32_t> none_;
};

// Even-odd location of q against a closed ring: inside, outside, or on an edge.
enum class Where { Outside, Inside, Boundary };
Where locate(const P2& q, const std::vector<P2>& ring);

// The same against the edges pts[i] -> pts[next(i)]: several rings one after
// another in pts (a face with holes), next(i) the corner after i in its ring.
template <class Next>
Where locate_edges(const P2& q, const std::vector<P2>& pts, Next&& next) {
  bool inside = false;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const P2& a = pts[i];
    const P2& b = pts[next(i)];
    if (on_segment(q, a, b)) return Where::Boundary;
    // Half-open rule on y: each crossing of the rightward ray is counted once.
    if ((a.y > q.y) != (b.y > q.y)) {
      const int o = orient(a, b, q);
      if (b.y > a.y ? o > 0 : o < 0) inside = !inside;
    }
  }
  return inside ? Where::Inside : Where::Outside;
}

// How two closed segments (each of positive length) meet.
enum class Meet { None, Point, Overlap };
Meet meet(const P2& a, const P2& b, const P2& c, const P2& d, P2* point = nullptr);

}  // namespace vismap_check
