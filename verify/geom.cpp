#include "verify/geom.h"

#include "verify/rational.h"

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

namespace {

// n/d = p - q with d > 0, unreduced.
void diff(const mpq_class& p, const mpq_class& q, mpz_class& n, mpz_class& d) {
  mpz_mul(n.get_mpz_t(), p.get_num_mpz_t(), q.get_den_mpz_t());
  mpz_submul(n.get_mpz_t(), q.get_num_mpz_t(), p.get_den_mpz_t());
  mpz_mul(d.get_mpz_t(), p.get_den_mpz_t(), q.get_den_mpz_t());
}

}  // namespace

int orient(const P2& o, const P2& a, const P2& b) {
  thread_local mpz_class n1, d1, n2, d2, n3, d3, n4, d4, l, r;
  diff(a.x, o.x, n1, d1);
  diff(b.y, o.y, n2, d2);
  diff(a.y, o.y, n3, d3);
  diff(b.x, o.x, n4, d4);
  // n1 n2 / (d1 d2) - n3 n4 / (d3 d4): compare n1 n2 d3 d4 with n3 n4 d1 d2.
  mpz_mul(l.get_mpz_t(), n1.get_mpz_t(), n2.get_mpz_t());
  if (sgn(l) != 0) {
    mpz_mul(l.get_mpz_t(), l.get_mpz_t(), d3.get_mpz_t());
    mpz_mul(l.get_mpz_t(), l.get_mpz_t(), d4.get_mpz_t());
  }
  mpz_mul(r.get_mpz_t(), n3.get_mpz_t(), n4.get_mpz_t());
  if (sgn(r) != 0) {
    mpz_mul(r.get_mpz_t(), r.get_mpz_t(), d1.get_mpz_t());
    mpz_mul(r.get_mpz_t(), r.get_mpz_t(), d2.get_mpz_t());
  }
  int c = cmp(l, r);
  return c > 0 ? 1 : c < 0 ? -1 : 0;
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

void BoxGrid::build(const std::vector<Box>& boxes) {
  cells_.clear();
  n_ = 0;
  if (boxes.empty()) return;
  Box all = boxes[0];
  for (const Box& b : boxes) {
    if (b.xmin < all.xmin) all.xmin = b.xmin;
    if (b.xmax > all.xmax) all.xmax = b.xmax;
    if (b.ymin < all.ymin) all.ymin = b.ymin;
    if (b.ymax > all.ymax) all.ymax = b.ymax;
  }
  n_ = 1;
  while (n_ < 64 && n_ * n_ < 4 * static_cast<long>(boxes.size())) ++n_;
  x0_ = all.xmin;
  y0_ = all.ymin;
  cw_ = (all.xmax - all.xmin) / n_;
  ch_ = (all.ymax - all.ymin) / n_;
  if (cw_ == 0) cw_ = 1;
  if (ch_ == 0) ch_ = 1;
  cells_.assign(static_cast<std::size_t>(n_ * n_), {});
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const Box& b = boxes[i];
    int c0 = cell(b.xmin, x0_, cw_), c1 = cell(b.xmax, x0_, cw_);
    int r0 = cell(b.ymin, y0_, ch_), r1 = cell(b.ymax, y0_, ch_);
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c)
        cells_[static_cast<std::size_t>(r * n_ + c)].push_back(static_cast<std::uint32_t>(i));
  }
}

// floor((v - lo) / size), clamped to the grid: a point outside every box may
// land in an edge cell, whose boxes are then tested and rejected.
int BoxGrid::cell(const mpq_class& v, const mpq_class& lo, const mpq_class& size) const {
  mpq_class t = (v - lo) / size;
  mpz_class f;
  mpz_fdiv_q(f.get_mpz_t(), t.get_num_mpz_t(), t.get_den_mpz_t());
  if (f < 0) return 0;
  if (f >= n_) return n_ - 1;
  return static_cast<int>(f.get_si());
}

const std::vector<std::uint32_t>& BoxGrid::near(const P2& q) const {
  if (n_ == 0) return none_;
  return cells_[static_cast<std::size_t>(cell(q.y, y0_, ch_) * n_ + cell(q.x, x0_, cw_))];
}

Where locate(const P2& q, const std::vector<P2>& ring) {
  const std::size_t n = ring.size();
  return locate_edges(q, ring, [n](std::size_t i) { return i + 1 == n ? 0 : i + 1; });
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
