#include "tests/checker/geom.h"

#include "tests/checker/rational.h"

namespace vismap_check {

std::string str(const P2& p) { return "(" + str(p.x) + ", " + str(p.y) + ")"; }

mpq_class cross(const P2& o, const P2& a, const P2& b) {
  mpq_class r = (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  return r;
}

mpq_class cross_dir(const P2& d1, const P2& d2) {
  mpq_class r = d1.x * d2.y - d1.y * d2.x;
  return r;
}

bool on_segment(const P2& q, const P2& a, const P2& b) {
  if (q.x < std::min(a.x, b.x) || q.x > std::max(a.x, b.x)) return false;
  if (q.y < std::min(a.y, b.y) || q.y > std::max(a.y, b.y)) return false;
  return orient(a, b, q) == 0;
}

mpq_class area2(const std::vector<P2>& ring) {
  mpq_class s = 0;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    const P2& a = ring[i];
    const P2& b = ring[(i + 1) % n];
    s += a.x * b.y - a.y * b.x;
  }
  return s;
}

Box box_of(const std::vector<P2>& pts) {
  Box b{pts[0].x, pts[0].x, pts[0].y, pts[0].y};
  for (const P2& p : pts) {
    if (p.x < b.xmin) b.xmin = p.x;
    if (p.x > b.xmax) b.xmax = p.x;
    if (p.y < b.ymin) b.ymin = p.y;
    if (p.y > b.ymax) b.ymax = p.y;
  }
  return b;
}

Box box_of(const P2& a, const P2& b) {
  return Box{std::min(a.x, b.x), std::max(a.x, b.x), std::min(a.y, b.y), std::max(a.y, b.y)};
}

Where locate(const P2& q, const std::vector<P2>& ring) {
  bool inside = false;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    const P2& a = ring[i];
    const P2& b = ring[(i + 1) % n];
    if (on_segment(q, a, b)) return Where::Boundary;
    // Half-open rule on y: each crossing of the rightward ray is counted once.
    if ((a.y > q.y) != (b.y > q.y)) {
      int o = orient(a, b, q);
      if (b.y > a.y ? o > 0 : o < 0) inside = !inside;
    }
  }
  return inside ? Where::Inside : Where::Outside;
}

Meet meet(const P2& a, const P2& b, const P2& c, const P2& d, P2* point) {
  int o1 = orient(a, b, c), o2 = orient(a, b, d);
  int o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 == 0 && o2 == 0) {   // collinear: compare extents along the line
    bool use_x = a.x != b.x;
    const mpq_class& a0 = use_x ? a.x : a.y;
    const mpq_class& b0 = use_x ? b.x : b.y;
    const mpq_class& c0 = use_x ? c.x : c.y;
    const mpq_class& d0 = use_x ? d.x : d.y;
    mpq_class lo = std::max(std::min(a0, b0), std::min(c0, d0));
    mpq_class hi = std::min(std::max(a0, b0), std::max(c0, d0));
    if (lo > hi) return Meet::None;
    if (lo < hi) return Meet::Overlap;
    if (point) {
      for (const P2* p : {&a, &b, &c, &d})
        if ((use_x ? p->x : p->y) == lo) { *point = *p; break; }
    }
    return Meet::Point;
  }
  if (o1 * o2 > 0 || o3 * o4 > 0) return Meet::None;
  if (point) {
    if (o1 == 0) *point = c;
    else if (o2 == 0) *point = d;
    else if (o3 == 0) *point = a;
    else if (o4 == 0) *point = b;
    else {
      mpq_class t = cross(c, a, d) / (cross(c, a, d) - cross(c, b, d));
      point->x = a.x + t * (b.x - a.x);
      point->y = a.y + t * (b.y - a.y);
    }
  }
  return Meet::Point;
}

}  // namespace vismap_check
