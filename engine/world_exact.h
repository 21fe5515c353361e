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
#include <limits>
#include <optional>

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

// The sign of value(N) for N = CGAL::Interval_nt<false> under upward rounding
// (a filter: an interval around the value) where it tells, else for N =
// CGAL::Mpzf (exact). value: a generic lambda of a number type's zero.
template <class Value>
int filtered_world_sign(Value&& value) {
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const CGAL::Interval_nt<false> d = value(CGAL::Interval_nt<false>(0));
    if (d.inf() > 0) return 1;
    if (d.sup() < 0) return -1;
  }
  return value(CGAL::Mpzf(0)).sign();
}

// ((q - p) x (r - p)) . ((q - p) x w): for r and w in (a direction parallel
// to) one plane with the line pq, positive where r lies on w's side of the
// line, negative on the other, 0 where r is on it.
template <class N>
N beside_line(const Vec3& p, const Vec3& q, const Vec3& r, const std::array<N, 3>& w) {
  const std::array<N, 3> n = normal_of<N>(p, q, r);
  const N dx = N(q.x) - N(p.x), dy = N(q.y) - N(p.y), dz = N(q.z) - N(p.z);
  return n[0] * (dy * w[2] - dz * w[1]) + n[1] * (dz * w[0] - dx * w[2]) + n[2] * (dx * w[1] - dy * w[0]);
}

// For r and s in one plane with the line pq, exact: +1 where they lie on one
// side of it, -1 on opposite sides, 0 where one is on the line.
inline int same_side_of_line(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
  return filtered_world_sign([&](auto zero) {
    using N = decltype(zero);
    return beside_line<N>(p, q, r, {N(s.x) - N(p.x), N(s.y) - N(p.y), N(s.z) - N(p.z)});
  });
}

// For r in a plane with the line pq and the direction a x b (the exact cross
// product of two double vectors), exact: +1 where r lies on that direction's
// side of the line, -1 on the other, 0 on it.
inline int side_of_line_toward(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& a, const Vec3& b) {
  return filtered_world_sign([&](auto zero) {
    using N = decltype(zero);
    return beside_line<N>(p, q, r, normal_of<N>(Vec3{0, 0, 0}, a, b));
  });
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

// A facet's unit normal, ((p - o) x (q - o)) / |(p - o) x (q - o)| rounded to
// floats, and an upper bound on its distance from the exact one: infinity
// where none is known. 16 bytes per facet that decide most crease tests (the
// angle between two facets' normals against a threshold) without reading the
// facets' corners, which a mesh's edges reach in no useful order.
struct UnitNormal {
  std::array<float, 3> n{};
  float err = std::numeric_limits<float>::infinity();
};

// The estimate of (p - o) x (q - o)'s direction. Bounds (u = 2^-53), where
// every component of a = p - o and b = q - o is at most 2^200 (nothing
// overflows below): a and b are off by u relatively (exact where they are
// subnormal), and each component of the normal m computed from them by at most
// 4.01 u (|a_j b_k| + |a_k b_j|) plus 2^-1072 (products that underflow), so
// |m - N| <= B = 8 u S + 2^-1000, with S the sum of those six products
// (computed: 2x margin). Where L = |m| as computed is at least 2^-400 (the
// squares that underflow then count for nothing), it is off by 3u, and
// |N| >= 0.999 L - B > 0.749 L where B < 0.2497 L (else nothing is kept), and
// m / |m| is off from N / |N| by at most 2 |m - N| / |N| < 2.68 B / L; scaling
// by 1 / L as computed adds 6u, and rounding to floats 2^-24 (1 + 6u). The
// sum, with a 1.001 margin that also covers its own roundings (and 1 / L's: 2.7
// for 2.68), is kept where it is below 1/4.
inline UnitNormal unit_normal(const Vec3& o, const Vec3& p, const Vec3& q) {
  UnitNormal out;
  const double a[3] = {p.x - o.x, p.y - o.y, p.z - o.z}, b[3] = {q.x - o.x, q.y - o.y, q.z - o.z};
  const double big = std::max({std::abs(a[0]), std::abs(a[1]), std::abs(a[2]), std::abs(b[0]), std::abs(b[1]), std::abs(b[2])});
  if (!(big <= 0x1p200)) return out;   // (NaN too)
  const double m[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const double S = std::abs(a[1] * b[2]) + std::abs(a[2] * b[1]) + std::abs(a[2] * b[0]) + std::abs(a[0] * b[2]) +
                   std::abs(a[0] * b[1]) + std::abs(a[1] * b[0]);
  const double B = 8 * 0x1p-53 * S + 0x1p-1000, L = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
  if (!(L >= 0x1p-400 && B < 0.2497 * L)) return out;
  const double inv = 1 / L, err = (2.7 * B * inv + 0x1p-24 * 1.001) * 1.001;
  if (!(err < 0.25)) return out;
  for (int i = 0; i < 3; ++i) out.n[static_cast<std::size_t>(i)] = static_cast<float>(m[i] * inv);
  out.err = static_cast<float>(err * (1 + 0x1p-20));   // (rounded to nearest: the margin keeps it above)
  return out;
}

// Whether two facets whose unit normals are estimated by x and y meet at a
// crease at cosine c (the cosine of the angle between their exact normals is
// below c), where the estimates tell; nullopt where they cannot. The exact unit
// normals n_x, n_y: |x.n . y.n - n_x . n_y| <= ex |y.n| + ey |n_x| <= ex (1 +
// ey) + ey; the dot product of floats in doubles (exact products, two
// roundings) adds at most 2.01 u (1 + ex)(1 + ey) < 2^-50 (errors below 1/4).
// The bound, rounded (3u), is kept above that by its 1 + 2^-40 margin, and
// c - dot (or dot - c) above the bound only where the real difference is.
inline std::optional<bool> crease_from_normals(const UnitNormal& x, const UnitNormal& y, double c) {
  const double ex = x.err, ey = y.err;
  if (!(ex < 0.25 && ey < 0.25)) return std::nullopt;
  const double dot = static_cast<double>(x.n[0]) * y.n[0] + static_cast<double>(x.n[1]) * y.n[1] +
                     static_cast<double>(x.n[2]) * y.n[2];
  const double bound = (ex + ey + ex * ey) * (1 + 0x1p-40) + 0x1p-50;
  if (c - dot > bound) return true;
  if (dot - c > bound) return false;
  return std::nullopt;
}

}  // namespace vismap::engine::world
