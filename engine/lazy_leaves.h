// Kernel numbers whose interval is known at once and whose exact rational is
// computed only if a predicate's filter fails or the value is written: the
// projected coordinates of input vertices, and the coefficients of a facet's
// depth plane where a construction takes them as numbers (the plane itself is
// intervals, its exact values made on demand: ExactSource::plane_of). Most
// are never needed exactly (an oblique view of a mesh asks for a few in a
// thousand), so the projection does no rational arithmetic at all.
// Internal to screen_scene.cpp (CGAL's lazy representations).
#pragma once
#include <CGAL/Mpzf.h>

#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <utility>
#include <vector>

#include "engine/exact_kernel.h"
#include "engine/image_values.h"
#include "engine/scene.h"

namespace vismap::exact {
VISMAP_KERNEL_BEGIN

// (row . (p, 1)) * 2^k exactly, as a binary float of any length (sums and
// products of doubles: no division, no gcd).
inline CGAL::Mpzf projected_mpzf(const std::array<double, 4>& row, const Vec3& p, int k) {
  CGAL::Mpzf s = CGAL::Mpzf(row[0]) * CGAL::Mpzf(p.x) + CGAL::Mpzf(row[1]) * CGAL::Mpzf(p.y) +
                 CGAL::Mpzf(row[2]) * CGAL::Mpzf(p.z) + CGAL::Mpzf(row[3]);
  // 2^k as two doubles (|k| may exceed a double's exponent range).
  if (k != 0) s = s * CGAL::Mpzf(std::ldexp(1.0, k / 2)) * CGAL::Mpzf(std::ldexp(1.0, k - k / 2));
  return s;
}

// The doubles next to x upwards and downwards (x finite), as std::nextafter
// towards +-infinity gives them, without its call.
inline double next_up(double x) {
  if (x == 0) return std::numeric_limits<double>::denorm_min();
  const auto bits = std::bit_cast<std::int64_t>(x);
  return std::bit_cast<double>(x > 0 ? bits + 1 : bits - 1);
}
inline double next_down(double x) { return -next_up(-x); }

// The interval around (row . (p, 1)) * 2^k that projected_mpzf's gives (the
// exact value rounded down and up: one ulp, or a point where it is a double),
// from doubles alone: each product split exactly in two (fma), the seven parts
// summed as in twice the precision (as Ogita, Rump and Oishi's Sum2: two-sum
// errors gathered), and the sum's last rounding error, told apart from the
// gathered errors' own (< 2^-100 of the parts' size), says on which side of
// the rounded sum the exact value lies. No GMP number is made. (The same
// interval, so that filters decide as they did: wider ones send more
// predicates to exact values, and a lazy construction's interval, refined when
// one is evaluated, then changes later filters' outcomes by the order in which
// threads got there.) False where it cannot tell (a sum that cancels to within
// the gathered errors' own error of a double) or a product or the scale could
// leave the range in which this holds: the caller then takes projected_mpzf's.
inline bool projected_bounds(const std::array<double, 4>& row, const Vec3& p, int k, double& lo, double& hi) {
  if (!(std::abs(row[3]) < 0x1p900)) return false;
  // The three products and their errors (fma: exact, each product being far
  // from underflow), side by side.
  double prod[3], low[3];
  const double v[3] = {p.x, p.y, p.z};
  for (int c = 0; c < 3; ++c) {
    const double m = row[static_cast<std::size_t>(c)];
    prod[c] = m * v[c];
    if (prod[c] != 0 && !(std::abs(prod[c]) > 0x1p-900 && std::abs(prod[c]) < 0x1p900)) return false;
    low[c] = std::fma(m, v[c], -prod[c]);
  }
  // The four large parts summed in a tree of two-sums (x + y = s + q exactly),
  // two at once, then one: value = sum + the three q + the three low parts,
  // exactly. (Not a chain of six two-sums, each waiting for the last: the
  // image bounds of a 10^6-triangle terrain, 1.5 M coordinates, took 72 ms
  // that way, 64 this way.)
  auto two_sum = [](double x, double y, double& q) {
    const double s = x + y, b = s - x;
    q = (x - (s - b)) + (y - b);
    return s;
  };
  double q[3];
  const double left = two_sum(prod[0], prod[1], q[0]), right = two_sum(prod[2], row[3], q[1]);
  const double sum = two_sum(left, right, q[2]);
  const double size = std::abs(row[3]) + std::abs(prod[0]) + std::abs(prod[1]) + std::abs(prod[2]) +
                      std::abs(low[0]) + std::abs(low[1]) + std::abs(low[2]);
  if (q[0] == 0 && q[1] == 0 && q[2] == 0 && low[0] == 0 && low[1] == 0 && low[2] == 0) {
    lo = hi = sum;   // (no part lost: the sum is the value)
  } else {
    // The six small parts, each at most u times a large part or partial sum
    // (u = 2^-53), add up to err with an error |e| <= gamma_5 * 4u size < 2^-101 size.
    const double err = (q[0] + q[1]) + (q[2] + ((low[0] + low[1]) + low[2]));
    // value = result + r + e exactly, r the last rounding's error (two-sum).
    double r;
    const double result = two_sum(sum, err, r);
    const double tail = size * 0x1p-100;
    if (r > tail) {
      lo = result;
      hi = next_up(result);
    } else if (r < -tail) {
      lo = next_down(result);
      hi = result;
    } else {
      return false;   // (the value is within the sum's error of a double: rare, see above)
    }
  }
  if (k != 0) {
    // (A power of two as a double where k is in its range: the products are
    // then ldexp's, exact wherever the test below lets them through.)
    const double scale = k >= -1022 && k <= 1023 ? std::bit_cast<double>(static_cast<std::uint64_t>(k + 1023) << 52) : 0;
    const double lo0 = lo, hi0 = hi;
    lo = scale != 0 ? lo * scale : std::ldexp(lo, k);
    hi = scale != 0 ? hi * scale : std::ldexp(hi, k);
    if ((lo == 0) != (lo0 == 0) || (hi == 0) != (hi0 == 0)) return false;   // (underflowed to 0)
    // (Exact unless it leaves the normal range.)
    for (double x : {lo, hi})
      if (x != 0 && !(std::abs(x) >= 0x1p-1000 && std::abs(x) < 0x1p1000)) return false;
  }
  return true;
}

// What the lazy leaves' exact values are computed from, on demand: the input's
// vertices, the view, the screen scale, and per facet three input vertices that
// span its plane in the world. (The screen scene owns it: it outlives every
// leaf, which refers to it instead of keeping copies.)
struct ExactSource {
  const std::vector<Vec3>* vertices = nullptr;
  std::array<std::array<double, 4>, 4> m{};   // the view matrix
  bool perspective = false;
  int k = 0;                                   // the screen scale: times 2^k
  std::vector<std::array<std::uint32_t, 3>> spanning;
  // Each facet's plane once a predicate has needed it (plane_of; null before).
  mutable std::vector<std::atomic<const std::array<mpq_class, 3>*>> planes;

  ExactSource() = default;
  ExactSource(const ExactSource&) = delete;
  ExactSource& operator=(const ExactSource&) = delete;
  ~ExactSource() {
    for (auto& p : planes) delete p.load();
  }
  // Room for n facets' spanning corners and planes.
  void reserve_facets(std::size_t n) {
    spanning.resize(n);
    planes = std::vector<std::atomic<const std::array<mpq_class, 3>*>>(n);
  }

  // Row r of the view applied to input vertex v, times 2^k if scaled (Mpzf below).
  CGAL::Mpzf row_at(int r, std::uint32_t v, bool scaled) const;
  // Input vertex v's image coordinate r as the canonical rational written: row
  // r applied to it, times 2^k if scaled; in perspective (N / W) 2^k, W row 3.
  // Machine integers where the values fit (image_values.h), else binary floats
  // and GMP's rationals.
  mpq_class image_exact(int r, std::uint32_t v, bool scaled) const;
  mpq_class perspective_exact(int r, std::uint32_t v) const;
  // Whether input vertices a and b have one screen coordinate r (0: x, 1: y) in
  // an orthographic view, told by the world with no arithmetic: equal in every
  // coordinate the row reads (only where it says so). A view along an axis puts
  // many images on one screen line, whose coordinate is not a double where the
  // row's entry is not a power of two, and no interval filter tells them equal.
  bool same_screen_coordinate(std::uint32_t a, std::uint32_t b, int r) const {
    return !perspective && agree_where_read(a, b, r, r);
  }
  // Whether input vertices a and b are equal in every world coordinate that
  // row r or row s of the view reads (a nonzero entry): those rows then give
  // both one value, with no arithmetic.
  bool agree_where_read(std::uint32_t a, std::uint32_t b, int r, int s) const {
    const auto &one = m[static_cast<std::size_t>(r)], &other = m[static_cast<std::size_t>(s)];
    const Vec3 &p = (*vertices)[a], &q = (*vertices)[b];
    auto read = [&](std::size_t i) { return one[i] != 0 || other[i] != 0; };
    return (!read(0) || p.x == q.x) && (!read(1) || p.y == q.y) && (!read(2) || p.z == q.z);
  }

  // Whether input vertices a and b (in front of the eye) have one screen
  // coordinate r (0: x, 1: y), decided exactly without the images' rationals:
  // orthographic, row r applied to both; in perspective N_a W_b = N_b W_a (N
  // row r, W row 3; the screen scale is common), binary floats, no gcd. (A
  // perspective view along an axis puts the edges of parts aligned with the
  // axes on screen verticals, whose ends no interval tells equal in x.)
  bool screen_coordinates_equal(std::uint32_t a, std::uint32_t b, int r) const {
    if (!perspective)
      return agree_where_read(a, b, r, r) || (row_at(r, a, false) - row_at(r, b, false)).sign() == 0;
    // (N and W equal where the two agree in every coordinate that row r or W
    // reads: most screen verticals.)
    if (agree_where_read(a, b, r, 3)) return true;
    return (row_at(r, a, false) * row_at(3, b, false) - row_at(r, b, false) * row_at(3, a, false)).sign() == 0;
  }

  // In an orthographic view, the sign of the screen cross product of the images
  // of b - a and d - c (input vertices): (r.v)(u.w) - (u.v)(r.w) = (r x u).(v x w)
  // (Binet-Cauchy), r and u the rows giving x and y, v = b - a, w = d - c; the
  // screen scale 2^k, on both coordinates, leaves the sign. Segments along world
  // axes with no arithmetic, else in binary floats (no gcd, no image's exact
  // value made). (Asked where intervals on the images failed: mostly exact
  // zeros, which a filter on doubles would only delay.)
  int screen_cross_sign(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) const {
    using M = CGAL::Mpzf;
    const Vec3 &A = (*vertices)[a], &B = (*vertices)[b], &C = (*vertices)[c], &D = (*vertices)[d];
    const std::array<M, 3>& n = sight();
    // Each along one world axis (a difference of doubles is 0 exactly where
    // they are equal): along the same one, parallel; along axes i and j, v x w
    // is v_i w_j (or its negative) times the third axis, so the sign is that
    // of (r x u) on it times the signs of v_i and w_j. No arithmetic on the
    // coordinates (views along a plane of two axes see those two as parallel).
    auto axis = [](const Vec3& p, const Vec3& q, int& sign) {
      const bool x = p.x != q.x, y = p.y != q.y, z = p.z != q.z;
      if (x + y + z != 1) return -1;
      const int k = x ? 0 : y ? 1 : 2;
      sign = coordinate(q, k) > coordinate(p, k) ? 1 : -1;
      return k;
    };
    int sv = 0, sw = 0;
    const int i = axis(A, B, sv), j = axis(C, D, sw);
    if (i >= 0 && j >= 0) {
      if (i == j) return 0;
      const int third = 3 - i - j, i1 = (third + 1) % 3;   // (i1, i2, third) cyclic
      return n[static_cast<std::size_t>(third)].sign() * sv * sw * (i == i1 ? 1 : -1);
    }
    // One along axis i, the other q - p (a lattice's edges and the segments
    // between its corners): (e_i x (q - p)) . n, times the sign of the first's
    // length, negated where it is the second.
    if (i >= 0) return sv * axis_cross(i, C, D);
    if (j >= 0) return -sw * axis_cross(j, A, B);
    const M vx = M(B.x) - M(A.x), vy = M(B.y) - M(A.y), vz = M(B.z) - M(A.z);
    const M wx = M(D.x) - M(C.x), wy = M(D.y) - M(C.y), wz = M(D.z) - M(C.z);
    const M cx = vy * wz - vz * wy, cy = vz * wx - vx * wz, cz = vx * wy - vy * wx;
    if (cx.sign() == 0 && cy.sign() == 0 && cz.sign() == 0) return 0;
    return (n[0] * cx + n[1] * cy + n[2] * cz).sign();
  }

  // sign((e_i x (q - p)) . n), n = r x u: (q - p)_j n_k - (q - p)_k n_j with
  // (i, j, k) cyclic (e_i x e_j = e_k). Where n_j or n_k is 0 (a view in a plane
  // of two axes), a comparison of two doubles. Else a filter on doubles first,
  // then, where n_j = +-n_k (an isometric view: the exact zeros come from
  // there), the sign of a sum of four doubles in machine integers; else Mpzf.
  // (A lattice of boxes seen along its diagonal asks this millions of times.)
  int axis_cross(int i, const Vec3& p, const Vec3& q) const {
    using M = CGAL::Mpzf;
    const std::array<M, 3>& n = sight();
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const int nj = n[static_cast<std::size_t>(j)].sign(), nk = n[static_cast<std::size_t>(k)].sign();
    auto order = [&](int c) { return (coordinate(q, c) > coordinate(p, c)) - (coordinate(q, c) < coordinate(p, c)); };
    if (nj == 0) return nk * order(j);
    if (nk == 0) return -nj * order(k);
    if (const int s = cross_on_doubles(coordinate(q, j) - coordinate(p, j), coordinate(q, k) - coordinate(p, k), j, k))
      return s;
    if (const int alike = sight_alike_[static_cast<std::size_t>(i)]) {
      // n_j = alike n_k: the value is n_k ((q_j - p_j) - alike (q_k - p_k)).
      const double a = alike;
      int sign = 0;
      if (sum_sign({coordinate(q, j), -coordinate(p, j), -a * coordinate(q, k), a * coordinate(p, k)}, sign))
        return nk * sign;
    }
    return ((M(coordinate(q, j)) - M(coordinate(p, j))) * n[static_cast<std::size_t>(k)] -
            (M(coordinate(q, k)) - M(coordinate(p, k))) * n[static_cast<std::size_t>(j)])
        .sign();
  }
  // sign(a n_k - b n_j) where a and b are the rounded differences of doubles it
  // is asked of, told on doubles, or 0 where they cannot tell. In any rounding
  // mode the differences, the products and their difference are each off by
  // under 2^-52 of their value, n's doubles (Mpzf::to_double) by under 2^-51:
  // the result by under 11 2^-53 (|a n_k| + |b n_j|), a third of the bound.
  // (Products near underflow, infinities and NaNs: not told.)
  int cross_on_doubles(double a, double b, int j, int k) const {
    const double t1 = a * sight_approx_[static_cast<std::size_t>(k)], t2 = b * sight_approx_[static_cast<std::size_t>(j)];
    const double v = t1 - t2, bound = (std::abs(t1) + std::abs(t2)) * 0x1p-48;
    if (!(bound >= 0x1p-900)) return 0;
    return v > bound ? 1 : v < -bound ? -1 : 0;
  }
  // r x u, exact, from the view's rows (made once, on first use: m is set first),
  // with its doubles and which of its coordinates are equal or opposite
  // (sight_alike_[i]: n_j = alike n_k, (i, j, k) cyclic; 0 for neither).
  const std::array<CGAL::Mpzf, 3>& sight() const {
    std::call_once(sight_once_, [&] {
      using M = CGAL::Mpzf;
      const auto &r = m[0], &u = m[1];
      sight_ = {M(r[1]) * M(u[2]) - M(r[2]) * M(u[1]), M(r[2]) * M(u[0]) - M(r[0]) * M(u[2]),
                M(r[0]) * M(u[1]) - M(r[1]) * M(u[0])};
      for (std::size_t c = 0; c < 3; ++c) sight_approx_[c] = CGAL::to_double(sight_[c]);
      for (std::size_t i = 0; i < 3; ++i) {
        const M &nj = sight_[(i + 1) % 3], &nk = sight_[(i + 2) % 3];
        sight_alike_[i] = nj == nk ? 1 : nj == -nk ? -1 : 0;
      }
    });
    return sight_;
  }
  mutable std::once_flag sight_once_;
  mutable std::array<CGAL::Mpzf, 3> sight_;
  mutable std::array<double, 3> sight_approx_{};
  mutable std::array<int, 3> sight_alike_{};

  // Facet f's depth plane z = a x + b y + c on the (scaled) screen: the image of
  // its world plane. The three corners' homogeneous images H_i = M (p_i, 1) are
  // exact binary floats; the plane through them is pi with pi_c = (-1)^c times
  // the 3x3 minor without column c (pi . H_i = 0), so pi_x x + pi_y y + pi_z z +
  // pi_w = 0 on screen, and with coordinates times 2^k: a = -pi_x / pi_z,
  // b = -pi_y / pi_z, c = -2^k pi_w / pi_z (pi_z != 0: the facet is not edge-on).
  // No gcd before the three quotients.
  std::array<mpq_class, 3> plane(std::size_t f) const {
    using M = CGAL::Mpzf;
    std::array<std::array<M, 4>, 3> h;
    for (int i = 0; i < 3; ++i) {
      const Vec3& p = (*vertices)[spanning[f][static_cast<std::size_t>(i)]];
      for (int r = 0; r < 4; ++r)
        h[i][r] = r == 3 && !perspective ? M(1.0)
                                         : M(m[r][0]) * M(p.x) + M(m[r][1]) * M(p.y) + M(m[r][2]) * M(p.z) + M(m[r][3]);
    }
    auto minor = [&](int c0, int c1, int c2) {
      return h[0][c0] * (h[1][c1] * h[2][c2] - h[1][c2] * h[2][c1]) -
             h[0][c1] * (h[1][c0] * h[2][c2] - h[1][c2] * h[2][c0]) +
             h[0][c2] * (h[1][c0] * h[2][c1] - h[1][c1] * h[2][c0]);
    };
    const mpq_class px(minor(1, 2, 3)), py(-minor(0, 2, 3)), pz(minor(0, 1, 3)), pw(-minor(0, 1, 2));
    std::array<mpq_class, 3> abc{-px / pz, -py / pz, -pw / pz};
    if (k > 0) mpq_mul_2exp(abc[2].get_mpq_t(), abc[2].get_mpq_t(), static_cast<unsigned long>(k));
    if (k < 0) mpq_div_2exp(abc[2].get_mpq_t(), abc[2].get_mpq_t(), static_cast<unsigned long>(-k));
    return abc;
  }
  // Facet f's plane (as plane()), computed once, on whichever thread asks first,
  // and kept: a facet whose depth a predicate needs exactly is mostly asked again.
  const std::array<mpq_class, 3>& plane_of(std::size_t f) const {
    if (const auto* known = planes[f].load(std::memory_order_acquire)) return *known;
    const auto* made = new std::array<mpq_class, 3>(plane(f));
    const std::array<mpq_class, 3>* first = nullptr;
    if (planes[f].compare_exchange_strong(first, made, std::memory_order_acq_rel, std::memory_order_acquire))
      return *made;
    delete made;   // (another thread's came first)
    return *first;
  }
};

inline CGAL::Mpzf ExactSource::row_at(int r, std::uint32_t v, bool scaled) const {
  return projected_mpzf(m[static_cast<std::size_t>(r)], (*vertices)[v], scaled ? k : 0);
}

inline mpq_class ExactSource::image_exact(int r, std::uint32_t v, bool scaled) const {
  mpq_class q;
  if (Dyadic n; row_dyadic(m[static_cast<std::size_t>(r)], (*vertices)[v], n))
    set_dyadic(q.get_mpq_t(), n, scaled ? k : 0);
  else
    q = mpq_class(row_at(r, v, scaled));
  return q;
}

inline mpq_class ExactSource::perspective_exact(int r, std::uint32_t v) const {
  mpq_class q;
  const Vec3& p = (*vertices)[v];
  if (Dyadic n, w; row_dyadic(m[static_cast<std::size_t>(r)], p, n) && row_dyadic(m[3], p, w) && w.m != 0)
    set_quotient(q.get_mpq_t(), n, w, k);
  else
    q = mpq_class(row_at(r, v, true)) / mpq_class(row_at(3, v, false));
  return q;
}

#ifndef VISMAP_FLOAT_KERNEL
using ExactRep = CGAL::Lazy_exact_nt_rep<mpq_class>;
static_assert(std::is_same_v<FT, CGAL::Lazy_exact_nt<mpq_class>>, "the leaves below build mpq_class values");

// A leaf whose exact value the source computes: the interval now, the rational
// on demand, named by an item (a vertex or a facet), a row and a scale flag.
// (64 bytes: everything else is in the source.)
class SourceLeaf : public ExactRep {
 public:
  SourceLeaf(const Interval& i, const ExactSource& source, std::uint32_t item, int row, bool scaled = false)
      : ExactRep(i), source_(&source), item_(item), row_(static_cast<std::int8_t>(row)), scaled_(scaled) {}

 protected:
  void set_exact(mpq_class value) const {
    auto* pet = new Indirect(std::move(value));
    this->keep_at(pet);
    this->set_ptr(pet);
  }
  const ExactSource* source_;
  std::uint32_t item_;
  std::int8_t row_;
  bool scaled_;
};

// A projected coordinate of input vertex item_: row row_ of the view applied to
// it, times 2^k if scaled_ (the screen scale); its interval as tight as it can
// be (the exact value rounded down and up).
class ProjectedRep final : public SourceLeaf {
 public:
  using SourceLeaf::SourceLeaf;
  void update_exact() const override { set_exact(source_->image_exact(row_, item_, scaled_)); }
};

// A perspective screen coordinate of input vertex item_, (N / W) * 2^k with N
// row row_ and W row 3 of the view applied to it: its interval the quotient of
// the two exact binary floats' intervals.
class PerspectiveRep final : public SourceLeaf {
 public:
  using SourceLeaf::SourceLeaf;
  void update_exact() const override { set_exact(source_->perspective_exact(row_, item_)); }
};

// One coefficient of facet item_'s depth plane (row_ 0: a, 1: b, 2: c), made
// where a construction needs it as a number (DepthPlane::number): its interval
// the plane's, its exact value the source's plane_of (made once per facet).
class PlaneRep final : public SourceLeaf {
 public:
  using SourceLeaf::SourceLeaf;
  void update_exact() const override { set_exact(source_->plane_of(item_)[static_cast<std::size_t>(row_)]); }
};
#endif

#ifndef VISMAP_FLOAT_KERNEL
// The interval projected_number's value has (that of the number it makes).
inline Interval projected_interval(const ExactSource& source, std::uint32_t v, int r, bool scaled) {
  std::pair<double, double> i;
  if (!projected_bounds(source.m[static_cast<std::size_t>(r)], (*source.vertices)[v], scaled ? source.k : 0, i.first,
                        i.second))
    i = source.row_at(r, v, scaled).to_interval();
  return Interval(i.first, i.second);
}

// The interval of vertex v's W (row 3 of the view, unscaled), as the
// perspective quotients divide by it: a vertex's three coordinates share it.
inline Interval w_interval(const ExactSource& source, std::uint32_t v) {
  const Interval w = projected_interval(source, v, 3, false);
  // (W > 0: an interval reaching 0 would make the quotient's unbounded.)
  if (w.inf() > 0) return w;
  const std::pair<double, double> exact = source.row_at(3, v, false).to_interval();
  return Interval(exact.first, exact.second);
}

// The intervals of vertex v's three perspective coordinates (rows 0, 1, 2 over
// W, times 2^k; w: w_interval(source, v)): the rows' bounds on doubles rounded
// to nearest, then the three quotients under one switch of the rounding mode
// (a switch stalls the pipeline: one per coordinate was ~3 % of a perspective
// view of 10^5 squares).
inline std::array<Interval, 3> perspective_intervals(const ExactSource& source, std::uint32_t v, const Interval& w) {
  const Interval x = projected_interval(source, v, 0, true), y = projected_interval(source, v, 1, true),
                 z = projected_interval(source, v, 2, true);
  CGAL::Protect_FPU_rounding<true> upward;
  return {x / w, y / w, z / w};
}
#endif

// Row r of the view applied to input vertex v (times 2^k if scaled) as a kernel
// number: a double where it is one exactly (views along an axis), else a lazy
// leaf of the exact value.
inline FT projected_number(const ExactSource& source, std::uint32_t v, int r, bool scaled) {
#ifdef VISMAP_FLOAT_KERNEL
  const auto& row = source.m[static_cast<std::size_t>(r)];
  const Vec3& p = (*source.vertices)[v];
  return std::ldexp(row[0] * p.x + row[1] * p.y + row[2] * p.z + row[3], scaled ? source.k : 0);
#else
  const Interval i = projected_interval(source, v, r, scaled);
  if (i.is_point()) return FT(i.inf());
  return FT(new ProjectedRep(i, source, v, r, scaled));
#endif
}

// Row r over row 3 (W > 0) of the view applied to input vertex v, times 2^k, as
// a kernel number: a lazy leaf (a double where its interval is one), its
// interval q (perspective_intervals') (doubles on the float kernel).
#ifdef VISMAP_FLOAT_KERNEL
inline FT perspective_number(const ExactSource& source, std::uint32_t v, int r) {
  const auto &n = source.m[static_cast<std::size_t>(r)], &w = source.m[3];
  const Vec3& p = (*source.vertices)[v];
  return std::ldexp((n[0] * p.x + n[1] * p.y + n[2] * p.z + n[3]) / (w[0] * p.x + w[1] * p.y + w[2] * p.z + w[3]),
                    source.k);
}
#else
inline FT perspective_number(const ExactSource& source, std::uint32_t v, int r, const Interval& q) {
  if (q.is_point()) return FT(q.inf());
  return FT(new PerspectiveRep(q, source, v, r));
}
#endif

// The sign of row . (p, 1), exactly: from its bounds where they tell
// (projected_bounds: the exact value rounded down and up), else from the value.
inline int projected_sign(const std::array<double, 4>& row, const Vec3& p) {
#ifdef VISMAP_FLOAT_KERNEL
  const double v = row[0] * p.x + row[1] * p.y + row[2] * p.z + row[3];
  return (v > 0) - (v < 0);
#else
  double lo, hi;
  if (projected_bounds(row, p, 0, lo, hi)) {
    if (lo > 0) return 1;
    if (hi < 0) return -1;
  }
  return projected_mpzf(row, p, 0).sign();
#endif
}

// The depth plane of three screen points u, v, w with the given exact sign of
// the projected area (non-zero): z = a x + b y + c, intervals of its
// coefficients from the points' intervals (the float variant: its doubles);
// false where those intervals cannot tell the area's sign (the caller then
// tries other points).
inline bool depth_plane(const P3& u, const P3& v, const P3& w, std::array<Interval, 3>& abc) {
#ifdef VISMAP_FLOAT_KERNEL
  const double x1 = v.x - u.x, y1 = v.y - u.y, z1 = v.z - u.z, x2 = w.x - u.x, y2 = w.y - u.y, z2 = w.z - u.z;
  const double nz = x1 * y2 - y1 * x2;
  if (nz == 0) return false;
  const double a = (z1 * y2 - y1 * z2) / nz, b = (x1 * z2 - z1 * x2) / nz;
  abc = {Interval(a), Interval(b), Interval(u.z - a * u.x - b * u.y)};
  return true;
#else
  CGAL::Protect_FPU_rounding<true> upward;
  const Interval x0 = approx_of(u.x), y0 = approx_of(u.y), z0 = approx_of(u.z);
  const Interval x1 = approx_of(v.x) - x0, y1 = approx_of(v.y) - y0, z1 = approx_of(v.z) - z0;
  const Interval x2 = approx_of(w.x) - x0, y2 = approx_of(w.y) - y0, z2 = approx_of(w.z) - z0;
  const Interval nz = x1 * y2 - y1 * x2;
  if (nz.inf() <= 0 && nz.sup() >= 0) return false;
  abc[0] = (z1 * y2 - y1 * z2) / nz;
  abc[1] = (x1 * z2 - z1 * x2) / nz;
  abc[2] = z0 - abc[0] * x0 - abc[1] * y0;
  return true;
#endif
}

VISMAP_KERNEL_END
}  // namespace vismap::exact
