// World-space geometry on the input's doubles, in any number type N: CGAL's
// Interval_nt under upward rounding (a filter: an interval around the value) or
// CGAL::Mpzf (exact: differences and products of doubles are binary floats, so
// no gcd is ever taken). Used by culling (volumes), crease angles and the
// coplanarity of a vertex with a facet. Internal to the engine.
#pragma once
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>

#include "engine/scene.h"

namespace vismap::engine::world {

// (p - o) x (q - o).
template <class N>
std::array<N, 3> normal_of(const Vec3& o, const Vec3& p, const Vec3& q) {
  const N ax = N(p.x) - N(o.x), ay = N(p.y) - N(o.y), az = N(p.z) - N(o.z);
  const N bx = N(q.x) - N(o.x), by = N(q.y) - N(o.y), bz = N(q.z) - N(o.z);
  return {ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx};
}

// det(a - o, b - o, c - o): six times the signed volume of (o, a, b, c).
template <class N>
N det(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& c) {
  const std::array<N, 3> n = normal_of<N>(o, a, b);
  return n[0] * (N(c.x) - N(o.x)) + n[1] * (N(c.y) - N(o.y)) + n[2] * (N(c.z) - N(o.z));
}

// sign(det(a - o, b - o, c - o)), exact: on doubles where CGAL's static filter
// for Orientation_3 (Epick's bound, with its guards against underflow and
// overflow) settles it, on binary floats (Mpzf, no gcd) where it cannot. For
// predicates asked millions of times on a mesh (faces that may pierce each other).
inline int orientation(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& c) {
  const double ax = a.x - o.x, ay = a.y - o.y, az = a.z - o.z;
  const double bx = b.x - o.x, by = b.y - o.y, bz = b.z - o.z;
  const double cx = c.x - o.x, cy = c.y - o.y, cz = c.z - o.z;
  double mx = std::max({std::abs(ax), std::abs(bx), std::abs(cx)});
  double my = std::max({std::abs(ay), std::abs(by), std::abs(cy)});
  double mz = std::max({std::abs(az), std::abs(bz), std::abs(cz)});
  const double eps = 5.1107127829973299e-15 * mx * my * mz;
  const double d = ax * (by * cz - bz * cy) - bx * (ay * cz - az * cy) + cx * (ay * bz - az * by);
  if (mx > mz) std::swap(mx, mz);   // mx <= my <= mz
  if (my > mz) std::swap(my, mz);
  else if (my < mx) std::swap(mx, my);
  if (mx >= 1e-97 && mz < 1e102) {
    if (d > eps) return 1;
    if (d < -eps) return -1;
  }
  // All four points in one coordinate plane (a column of zero differences: faces
  // of axis-aligned boxes, a mesh's flat base): zero, with no arithmetic.
  if (mx == 0) return 0;
  return det<CGAL::Mpzf>(o, a, b, c).sign();
}

// Whether o, a and b lie on one line ((a - o) x (b - o) = 0), exact: a normal
// component clearly apart from 0 on doubles says no, else binary floats
// decide. (Each component, from rounded differences, two rounded products and
// a rounded difference, is off by at most about 8 u A B, u = 2^-53, A and B
// the largest |coordinate| of a - o and b - o: the bound below is four times
// that; within 2^-400..2^400 no product underflows to where it would not hold.)
inline bool collinear(const Vec3& o, const Vec3& a, const Vec3& b) {
  const double A = std::max({std::abs(a.x - o.x), std::abs(a.y - o.y), std::abs(a.z - o.z)});
  const double B = std::max({std::abs(b.x - o.x), std::abs(b.y - o.y), std::abs(b.z - o.z)});
  if (A >= 0x1p-400 && A <= 0x1p400 && B >= 0x1p-400 && B <= 0x1p400) {
    const double bound = 0x1p-48 * A * B;
    for (const double c : normal_of<double>(o, a, b))
      if (std::abs(c) > bound) return false;
  }
  const std::array<CGAL::Mpzf, 3> n = normal_of<CGAL::Mpzf>(o, a, b);
  return n[0].sign() == 0 && n[1].sign() == 0 && n[2].sign() == 0;
}

// orientation(o, a, b, p) for several points p against one plane: its normal
// (a - o) x (b - o) made once in doubles, then sign(n . (p - o)) where a static
// bound settles it (|error| <= 54 u A B C, u = 2^-53, with A, B, C the largest
// |coordinate| of a - o, b - o and p - o; taken as 2^-44 A B C), else
// orientation()'s, exact where it must be.
class PlaneSide {
 public:
  PlaneSide(const Vec3& o, const Vec3& a, const Vec3& b) : o_(o), a_(a), b_(b), n_(normal_of<double>(o, a, b)) {
    const double A = std::max({std::abs(a.x - o.x), std::abs(a.y - o.y), std::abs(a.z - o.z)});
    const double B = std::max({std::abs(b.x - o.x), std::abs(b.y - o.y), std::abs(b.z - o.z)});
    ab_ = A * B;
    usable_ = A >= 0x1p-300 && A <= 0x1p300 && B >= 0x1p-300 && B <= 0x1p300;
  }
  int operator()(const Vec3& p) const {
    if (usable_) {
      const double cx = p.x - o_.x, cy = p.y - o_.y, cz = p.z - o_.z;
      const double C = std::max({std::abs(cx), std::abs(cy), std::abs(cz)});
      if (C >= 0x1p-300 && C <= 0x1p300) {
        const double d = n_[0] * cx + n_[1] * cy + n_[2] * cz, bound = 0x1p-44 * ab_ * C;
        if (d > bound) return 1;
        if (d < -bound) return -1;
      }
    }
    return orientation(o_, a_, b_, p);
  }

 private:
  const Vec3 &o_, &a_, &b_;
  std::array<double, 3> n_;
  double ab_;
  bool usable_;
};

// Whether every coordinate of the points is at most 2^e in magnitude: interval
// products of degree up to about 1000 / e cannot overflow then. An interval with
// an infinite bound is not trusted (inf * 0 is NaN, which a later max can drop).
inline bool within(int e, std::initializer_list<const Vec3*> pts) {
  const double bound = std::ldexp(1.0, e);
  for (const Vec3* v : pts)
    if (!(std::abs(v->x) <= bound && std::abs(v->y) <= bound && std::abs(v->z) <= bound)) return false;
  return true;
}

}  // namespace vismap::engine::world
