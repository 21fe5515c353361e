// World-space geometry on the input's doubles, in any number type N: CGAL's
// Interval_nt under upward rounding (a filter: an interval around the value) or
// CGAL::Mpzf (exact: differences and products of doubles are binary floats, so
// no gcd is ever taken). Used by culling (volumes), crease angles and the
// coplanarity of a vertex with a facet. Internal to the engine.
#pragma once
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

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
