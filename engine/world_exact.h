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
  return det<CGAL::Mpzf>(o, a, b, c).sign();
}

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
