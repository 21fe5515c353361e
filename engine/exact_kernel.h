// The one place that names the kernel. Only the CGAL translation units of the
// engine include this; public headers stay free of CGAL.
//
// The kernel-dependent units (screen_scene, franklin_grid, franklin, map_builder)
// are compiled twice: normally with CGAL's Epeck (filtered predicates, lazy exact
// constructions), and with VISMAP_FLOAT_KERNEL defined on plain doubles
// (CGAL::Simple_cartesian<double>) for the benchmarks' float variant: the same code
// path on an inexact kernel, to show what exactness costs and what it buys. The two
// builds live in different inline namespaces, so both link into one program.
#pragma once
#ifndef VISMAP_EXACT_CONFIG_H
#error "engine/exact_config.h must come first (CMake force-includes it for vismap_core)"
#endif
#include <CGAL/Interval_nt.h>
#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>
#ifdef VISMAP_FLOAT_KERNEL
#include <CGAL/Simple_cartesian.h>
#define VISMAP_KERNEL_NS float_kernel
#else
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#define VISMAP_KERNEL_NS exact_kernel
#endif
// Opens / closes the kernel's inline namespace around kernel-dependent code.
#define VISMAP_KERNEL_BEGIN inline namespace VISMAP_KERNEL_NS {
#define VISMAP_KERNEL_END }

namespace vismap::exact {
VISMAP_KERNEL_BEGIN

#ifdef VISMAP_FLOAT_KERNEL
using K = CGAL::Simple_cartesian<double>;   // no filter, no exactness: the float variant
#else
using K = CGAL::Epeck;          // filtered predicates, lazy exact constructions
#endif
using FT = K::FT;
using P2 = K::Point_2;
using V2 = K::Vector_2;
using Seg2 = K::Segment_2;

// The exact value of a kernel number as a GMP rational (forces exact evaluation),
// a rational as a kernel number, and a number's interval approximation.
inline mpq_class to_mpq(const mpq_class& q) { return q; }
#ifdef VISMAP_FLOAT_KERNEL
inline mpq_class to_mpq(double x) { return mpq_class(x); }
inline FT from_mpq(const mpq_class& q) { return q.get_d(); }
inline CGAL::Interval_nt<false> approx_of(const FT& x) { return CGAL::Interval_nt<false>(x); }
#else
// (CGAL picks mpq_class or Boost's gmp_rational depending on what is included.)
template <class Boost_rational>
mpq_class to_mpq(const Boost_rational& q) { return mpq_class(q.backend().data()); }
inline mpq_class to_mpq(const FT& x) { return to_mpq(CGAL::exact(x)); }
inline FT from_mpq(const mpq_class& q) { return FT(q); }
inline CGAL::Interval_nt<false> approx_of(const FT& x) { return x.approx(); }
#endif

using Interval = CGAL::Interval_nt<false>;

#ifndef VISMAP_FLOAT_KERNEL
// compare(a, b) on their intervals, then their exact values, never counted:
// where threads share the numbers, a lazy number's interval narrows once some
// thread made its exact value, and a counted comparison (CGAL's) would count by
// which thread came first (the stats must not depend on the thread count).
inline CGAL::Comparison_result compare_uncounted(const FT& a, const FT& b) {
  const Interval ia = approx_of(a), ib = approx_of(b);
  if (ia.sup() < ib.inf()) return CGAL::SMALLER;
  if (ib.sup() < ia.inf()) return CGAL::LARGER;
  if (ia.is_point() && ib.is_point()) return CGAL::EQUAL;
  const auto &ea = CGAL::exact(a), &eb = CGAL::exact(b);
  if (ea == eb) return CGAL::EQUAL;   // (mostly equal: limbs compared, no product)
  return ea < eb ? CGAL::SMALLER : CGAL::LARGER;
}
#endif

// A point's coordinates as intervals (no lazy number built) and exactly.
#ifdef VISMAP_FLOAT_KERNEL
inline Interval approx_x(const P2& p) { return Interval(p.x()); }
inline Interval approx_y(const P2& p) { return Interval(p.y()); }
inline mpq_class exact_x(const P2& p) { return mpq_class(p.x()); }
inline mpq_class exact_y(const P2& p) { return mpq_class(p.y()); }
#else
inline Interval approx_x(const P2& p) { return p.approx().x(); }
inline Interval approx_y(const P2& p) { return p.approx().y(); }
inline mpq_class exact_x(const P2& p) { return to_mpq(CGAL::exact(p).x()); }
inline mpq_class exact_y(const P2& p) { return to_mpq(CGAL::exact(p).y()); }
#endif

// Whether two points share one representation (copies of one lazy point): then
// they are equal, with no predicate. (CGAL::identical on kernel points compares
// the objects' addresses, so copies would not count.)
#ifdef VISMAP_FLOAT_KERNEL
inline bool same_rep(const P2& a, const P2& b) { return &a == &b; }
#else
inline bool same_rep(const P2& a, const P2& b) { return a.identical(b); }
#endif

// Whether two points are equal: by representation, then by their coordinates'
// intervals (apart in x or in y: different), and only then by CGAL's equality.
// (That compares x first and throws where x alone is uncertain: every two
// points of a vertical screen line, which views with the up axis vertical are
// full of, went to exact numbers though their y told them apart.)
inline bool equal_points(const P2& a, const P2& b) {
  if (same_rep(a, b)) return true;
  auto apart = [](const Interval& p, const Interval& q) { return p.sup() < q.inf() || q.sup() < p.inf(); };
  if (apart(approx_x(a), approx_x(b)) || apart(approx_y(a), approx_y(b))) return false;
  return a == b;
}

// Order on points without C++ exceptions. CGAL's filtered predicates that
// branch on a comparison (lexicographic order, order along a line) throw one
// wherever an interval comparison is uncertain, ~2 us each; on a vertical
// screen line whose x is not a double, every comparison of x is (a city's
// buildings seen along an axis: a third of the whole run went to unwinding).
// These decide on the intervals, else on the exact values; counted as CGAL's.
#ifdef VISMAP_FLOAT_KERNEL
inline CGAL::Comparison_result compare_xy_exactly(const P2& a, const P2& b) { return CGAL::compare_xy(a, b); }
inline CGAL::Comparison_result compare_coordinate_exactly(const P2& a, const P2& b, bool along_x) {
  return along_x ? CGAL::compare_x(a, b) : CGAL::compare_y(a, b);
}
inline bool between_on_line(const P2& p, const P2& q, const P2& r, bool strictly) {
  return strictly ? CGAL::collinear_are_strictly_ordered_along_line(p, q, r)
                  : CGAL::collinear_are_ordered_along_line(p, q, r);
}
#else
// u against v where their bounds tell: apart, or one double.
inline bool told_by_bounds(const Interval& u, const Interval& v, CGAL::Comparison_result& c) {
  if (u.sup() < v.inf()) c = CGAL::SMALLER;
  else if (v.sup() < u.inf()) c = CGAL::LARGER;
  else if (u.is_point() && v.is_point()) c = CGAL::EQUAL;   // (not apart: the same double)
  else return false;
  return true;
}
// a and b lexicographically (x, then y).
inline CGAL::Comparison_result compare_xy_exactly(const P2& a, const P2& b) {
  ++filter_counts.calls;
  CGAL::Comparison_result c;
  if (told_by_bounds(approx_x(a), approx_x(b), c) &&
      (c != CGAL::EQUAL || told_by_bounds(approx_y(a), approx_y(b), c)))
    return c;
  ++filter_counts.exact;
  return CGAL::compare_xy(CGAL::exact(a), CGAL::exact(b));
}
// a and b by one coordinate (x where along_x, else y): copies of one point
// equal, then on the intervals (bounds compared: no rounding-mode switch, which
// CGAL's filtered compare_x and compare_y make at every call, ~40 ns), else on
// the exact values. For sorts of many points along a curve.
inline CGAL::Comparison_result compare_coordinate_exactly(const P2& a, const P2& b, bool along_x) {
  ++filter_counts.calls;
  if (same_rep(a, b)) return CGAL::EQUAL;   // (a point cut on several curves: one object)
  CGAL::Comparison_result c;
  if (told_by_bounds(along_x ? approx_x(a) : approx_y(a), along_x ? approx_x(b) : approx_y(b), c)) return c;
  ++filter_counts.exact;
  const auto &ea = CGAL::exact(a), &eb = CGAL::exact(b);
  return along_x ? CGAL::compare_x(ea, eb) : CGAL::compare_y(ea, eb);
}
// Whether q lies between p and r (strictly: not at either), the three known to
// lie on one line. Along a line, any coordinate that is not constant on it
// orders its points: one whose intervals set q apart from p and from r decides,
// or one that is a double in all three, unequal at p and r (q then may be at
// either end: edges along a line that share their ends, seen along an axis).
inline bool between_on_line(const P2& p, const P2& q, const P2& r, bool strictly) {
  ++filter_counts.calls;
  auto apart = [](const Interval& u, const Interval& v) { return u.sup() < v.inf() || v.sup() < u.inf(); };
  for (const auto coordinate : {approx_x, approx_y}) {
    const Interval ip = coordinate(p), iq = coordinate(q), ir = coordinate(r);
    if (apart(ip, iq) && apart(iq, ir)) return (ip.sup() < iq.inf()) == (iq.sup() < ir.inf());
    if (ip.is_point() && iq.is_point() && ir.is_point() && ip.inf() != ir.inf()) {
      const double lo = std::min(ip.inf(), ir.inf()), hi = std::max(ip.inf(), ir.inf()), at = iq.inf();
      return strictly ? lo < at && at < hi : lo <= at && at <= hi;
    }
  }
  ++filter_counts.exact;
  const auto &ep = CGAL::exact(p), &eq = CGAL::exact(q), &er = CGAL::exact(r);
  return strictly ? CGAL::collinear_are_strictly_ordered_along_line(ep, eq, er)
                  : CGAL::collinear_are_ordered_along_line(ep, eq, er);
}
#endif

// The sign of an expression: on the intervals of its operands if they decide it,
// else exactly in GMP rationals; counted like CGAL's own filters. For the hot
// predicates whose lazy form would build a tree of numbers at every call.
//
// Interval arithmetic needs the FPU rounding upward, and switching it costs far
// more (about 18 ns here) than the arithmetic (2 ns). A loop that calls many of
// these predicates and no CGAL predicate (CGAL's static filters assume rounding
// to nearest) holds one UpwardRounding for all of them; exact fallbacks then
// run with rounding to nearest again.
inline thread_local bool rounding_upward = false;
class UpwardRounding {
 public:
  UpwardRounding() : was_(rounding_upward) { rounding_upward = true; }
  ~UpwardRounding() { rounding_upward = was_; }
  UpwardRounding(const UpwardRounding&) = delete;
  UpwardRounding& operator=(const UpwardRounding&) = delete;
 private:
  CGAL::Protect_FPU_rounding<true> upward_;
  bool was_;
};
class NearestRounding {   // undoes an UpwardRounding for a scope
 public:
  NearestRounding() : old_(CGAL::FPU_get_and_set_cw(CGAL_FE_TONEAREST)), was_(rounding_upward) {
    rounding_upward = false;
  }
  ~NearestRounding() {
    CGAL::FPU_set_cw(old_);
    rounding_upward = was_;
  }
  NearestRounding(const NearestRounding&) = delete;
  NearestRounding& operator=(const NearestRounding&) = delete;
 private:
  CGAL::FPU_CW_t old_;
  bool was_;
};

// The interval side, with everything it calls inlined (CGAL's interval product
// is otherwise an out-of-line call in the hottest loops).
template <class OnIntervals>
[[gnu::flatten]] inline Interval on_intervals(OnIntervals& approx) {
  return approx();
}

// The sign an interval proves: it holds the exact value, so [0, 0] proves a
// zero as surely as [1, 2] a positive value (an exact zero of numbers that
// are doubles: a view along an axis, parts aligned on a lattice). Else
// nullopt: the exact value decides.
inline std::optional<CGAL::Sign> sign_of(const Interval& v) {
  if (v.inf() > 0) return CGAL::POSITIVE;
  if (v.sup() < 0) return CGAL::NEGATIVE;
  if (v.inf() == 0 && v.sup() == 0) return CGAL::ZERO;
  return std::nullopt;
}

template <class OnIntervals, class OnRationals>
CGAL::Sign filtered_sign(OnIntervals&& approx, OnRationals&& exact) {
  ++filter_counts.calls;
  if (rounding_upward) {
    if (const auto s = sign_of(on_intervals(approx))) return *s;
    ++filter_counts.exact;
    NearestRounding nearest;
    return static_cast<CGAL::Sign>(sgn(mpq_class(exact())));
  }
  {
    CGAL::Protect_FPU_rounding<true> upward;
    if (const auto s = sign_of(on_intervals(approx))) return *s;
  }
  ++filter_counts.exact;
  const mpq_class v = exact();
  return static_cast<CGAL::Sign>(sgn(v));
}

// sign((q - p) x (r - p)) for rational points, with no gcd: the determinant of
// the rows (x, y, 1), each row multiplied by its two (positive) denominators,
// on integers. (Rational arithmetic would normalise after every operation.)
inline int orient_sign(const mpq_class& px, const mpq_class& py, const mpq_class& qx, const mpq_class& qy,
                       const mpq_class& rx, const mpq_class& ry) {
  struct Row {
    mpz_class x, y, w;
  };
  auto row = [](const mpq_class& x, const mpq_class& y) {
    return Row{x.get_num() * y.get_den(), y.get_num() * x.get_den(), x.get_den() * y.get_den()};
  };
  const Row a = row(px, py), b = row(qx, qy), c = row(rx, ry);
  const mpz_class d = a.x * (b.y * c.w - b.w * c.y) - a.y * (b.x * c.w - b.w * c.x) + a.w * (b.x * c.y - b.y * c.x);
  return sgn(d);
}

#ifndef VISMAP_FLOAT_KERNEL
// A lazy point whose interval never narrows. CGAL refines a construction's
// interval once its exact value is made; for a point the threads share (a
// vertex image, a crossing of two curves) which thread made it first would then
// decide which later filters succeed, and the counts in the JSON must not depend
// on the thread count (a perspective view's images are quotients whose
// intervals are a few ulps wide: on a 10^6-triangle terrain the exact
// predicates counted varied from run to run on two threads). These keep the
// interval they were made with; the exact value is made on demand, once.
namespace steady_detail {
using PointRep = P2::Rep::Self_rep;
using ExactPoint = K::Exact_kernel::Point_2;
using ApproxPoint = K::Approximate_kernel::Point_2;
// A point with the interval `at` whose exact value is make(exact(args)...),
// made once, on demand; the interval stays. (One class for every such point:
// steady_point's, crossing_point's, frozen()'s.)
template <class Make, class... Args>
class KeptPoint final : public PointRep {
 public:
  KeptPoint(const ApproxPoint& at, Make make, const Args&... args) : PointRep(at), make_(make), args_(args...) {}
  void update_exact() const override {
    auto* pet = new PointRep::Indirect(
        std::apply([&](const Args&... a) { return ExactPoint(make_(CGAL::exact(a)...)); }, args_));
    this->keep_at(pet);
    this->set_ptr(pet);
    args_ = {};   // (their DAGs are not needed any more)
  }

 private:
  [[no_unique_address]] Make make_;
  mutable std::tuple<Args...> args_;
};
template <class Make, class... Args>
P2 kept_point(const ApproxPoint& at, Make make, const Args&... args) {
  return P2(P2::Rep(new KeptPoint<Make, Args...>(at, make, args...)));
}
inline bool bounded(const Interval& i) { return std::isfinite(i.inf()) && std::isfinite(i.sup()); }
inline bool bounded(const ApproxPoint& p) { return bounded(p.x()) && bounded(p.y()); }
}  // namespace steady_detail
// The point (x, y), made once: each lazy point made costs an allocation. (Where
// an interval is unbounded, which would never narrow, the point is made exact
// now, before any thread shares it.)
inline P2 steady_point(const FT& x, const FT& y) {
  if (x.approx().is_point() && y.approx().is_point()) return P2(x, y);   // (nothing to narrow)
  if (!steady_detail::bounded(x.approx()) || !steady_detail::bounded(y.approx())) {
    const P2 p(x, y);
    CGAL::exact(p);
    return p;
  }
  return steady_detail::kept_point(
      steady_detail::ApproxPoint(x.approx(), y.approx()),
      [](const auto& ex, const auto& ey) { return steady_detail::ExactPoint(ex, ey); }, x, y);
}
#else
inline P2 steady_point(const FT& x, const FT& y) { return P2(x, y); }
#endif

// Screen-space point with its depth: (x, y) on the screen, z = depth (smaller = nearer).
// The point (x, y) is built once, steady (steady_point: the threads share images).
struct P3 {
  FT x, y, z;
  P2 p;
  P3() = default;
  P3(const FT& x_, const FT& y_, const FT& z_) : x(x_), y(y_), z(z_), p(steady_point(x_, y_)) {}
  P3(const P2& q, const FT& z_) : x(q.x()), y(q.y()), z(z_), p(q) {}
  const P2& xy() const { return p; }
};

// A copy of a constructed point whose intervals never narrow. CGAL refines a
// lazy construction's interval once its exact value is made; for a point that
// threads share (an intersection line's end, made in one thread and cut and
// classified in others) which thread made it first would then decide which
// later filters succeed, and the counts in the JSON must not depend on the
// thread count. The copy keeps the interval it was made with and takes its
// exact value from the original, on demand. (Precomputing the exact values
// instead costs ~20% of a perspective view of a soup of triangles.)
#ifdef VISMAP_FLOAT_KERNEL
inline P2 frozen(const P2& p) { return p; }
inline P3 frozen(const P3& a) { return a; }
#else
namespace frozen_detail {
class Number final : public CGAL::Lazy_exact_nt_rep<mpq_class> {
 public:
  explicit Number(const FT& x) : CGAL::Lazy_exact_nt_rep<mpq_class>(x.approx()), x_(x) {}
  void update_exact() const override {
    auto* pet = new Indirect(CGAL::exact(x_));
    this->keep_at(pet);
    this->set_ptr(pet);
    x_ = FT();   // (the original's DAG is not needed any more)
  }
 private:
  mutable FT x_;
};
}  // namespace frozen_detail
// (An unbounded interval, which would never narrow, is made exact now, before
// any thread shares the value, as steady_point does.)
inline FT frozen(const FT& x) {
  if (x.approx().is_point()) return x;
  if (!steady_detail::bounded(x.approx())) {
    CGAL::exact(x);
    return x;
  }
  return FT(new frozen_detail::Number(x));
}
inline P2 frozen(const P2& p) {
  if (p.approx().x().is_point() && p.approx().y().is_point()) return p;
  if (!steady_detail::bounded(p.approx())) {
    CGAL::exact(p);
    return p;
  }
  return steady_detail::kept_point(p.approx(), [](const steady_detail::ExactPoint& e) { return e; }, p);
}
inline P3 frozen(const P3& a) {
  P3 r;
  r.x = frozen(a.x);
  r.y = frozen(a.y);
  r.z = frozen(a.z);
  r.p = frozen(a.p);
  return r;
}
#endif

// Depth at screen point p on the line from s to t (depth is affine along a
// screen line), interpolated along the line's dominant screen axis.
inline FT depth_along(const P3& s, const P3& t, const P2& p) {
  const bool use_x = CGAL::compare(CGAL::abs(t.x - s.x), CGAL::abs(t.y - s.y)) != CGAL::SMALLER;
  const FT lambda = use_x ? (p.x() - s.x) / (t.x - s.x) : (p.y() - s.y) / (t.y - s.y);
  return s.z + lambda * (t.z - s.z);
}

VISMAP_KERNEL_END
}  // namespace vismap::exact
