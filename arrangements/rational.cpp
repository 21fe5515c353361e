#include "arrangements/rational.h"

#include <cassert>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "arrangements/visibility_map.h"

namespace vismap {

namespace {

// q's digits after `out`, as GMP prints them ("n" when the denominator is 1).
void append_digits(std::string& out, const mpq_class& q) {
  const std::size_t at = out.size();
  out.resize(at + mpz_sizeinbase(q.get_num_mpz_t(), 10) + mpz_sizeinbase(q.get_den_mpz_t(), 10) + 3);
  mpq_get_str(out.data() + at, 10, q.get_mpq_t());
  out.resize(at + std::strlen(out.data() + at));
}

// The decimal digits of 2^k, made once per thread: an orthographic view's
// coordinates are fractions over powers of two, and a map's vertices share a
// few dozen of them (the denominator was half of each number's conversion).
const std::string& power_of_two_digits(mp_bitcnt_t k) {
  thread_local std::vector<std::string> made;
  if (k >= made.size()) made.resize(k + 1);
  std::string& digits = made[k];
  if (digits.empty()) {
    mpz_class p;
    mpz_setbit(p.get_mpz_t(), k);
    digits = p.get_str();
  }
  return digits;
}

// n/2^k's digits after `out`, as mpq_get_str prints them (n alone for k = 0).
void append_dyadic_digits(std::string& out, mpz_srcptr n, mp_bitcnt_t k) {
  const std::size_t at = out.size();
  out.resize(at + mpz_sizeinbase(n, 10) + 2);
  mpz_get_str(out.data() + at, 10, n);
  out.resize(at + std::strlen(out.data() + at));
  if (k == 0) return;
  out += '/';
  out += power_of_two_digits(k);
}

}  // namespace

void append_canonical(std::string& out, const mpq_class& q) {
  // Told without a gcd where the denominator is a power of two (an orthographic
  // view's coordinates): such a fraction is in lowest terms when its numerator
  // is odd or its denominator 1.
  const mpz_srcptr num = q.get_num_mpz_t(), den = q.get_den_mpz_t();
  const mp_bitcnt_t twos = mpz_scan1(den, 0);
  if (mpz_sgn(den) > 0 && mpz_sizeinbase(den, 2) == twos + 1 && (twos == 0 || mpz_odd_p(num))) {
    append_lowest_terms(out, q);
    return;
  }
  mpq_class c(q);
  c.canonicalize();   // lowest terms, positive denominator
  append_lowest_terms(out, c);
}

// Whether q is in the form GMP's arithmetic keeps it in: lowest terms, denominator
// positive (0 as 0/1).
bool in_lowest_terms(const mpq_class& q) {
  if (mpz_sgn(q.get_den_mpz_t()) <= 0) return false;
  mpz_class g;
  mpz_gcd(g.get_mpz_t(), q.get_num_mpz_t(), q.get_den_mpz_t());
  return g == 1;
}

void append_lowest_terms(std::string& out, const mpq_class& q) {
  assert(in_lowest_terms(q));
  const mpz_srcptr num = q.get_num_mpz_t(), den = q.get_den_mpz_t();
  const mp_bitcnt_t twos = mpz_scan1(den, 0);
  // (Denominators of 2^4096 and beyond, rare: GMP's own text; those digits are not kept.)
  if (mpz_sizeinbase(den, 2) == twos + 1 && twos < 4096) append_dyadic_digits(out, num, twos);
  else append_digits(out, q);
}

std::string canonical(const mpq_class& q) {
  std::string s;
  append_canonical(s, q);
  return s;
}

double nearest_double(const mpq_class& q) {
  const double d = q.get_d();   // towards zero: |d| <= |q| < the next double away from zero
  if (!std::isfinite(d) || mpq_class(d) == q) return d;
  const double inf = std::numeric_limits<double>::infinity();
  const double away = std::nextafter(d, q > 0 ? inf : -inf);
  // The midpoint between d and the next double; past the largest double, the
  // next one is where it would be (IEEE rounds to infinity beyond its midpoint).
  const mpq_class next = std::isinf(away) ? mpq_class(d) + (mpq_class(d) - mpq_class(std::nextafter(d, 0.0)))
                                          : mpq_class(away);
  const mpq_class mid = (mpq_class(d) + next) / 2;
  const int c = cmp(abs(q), abs(mid));
  if (c < 0) return d;
  if (c > 0) return away;
  std::int64_t bits;
  static_assert(sizeof bits == sizeof d);
  std::memcpy(&bits, &d, sizeof d);
  return bits % 2 == 0 ? d : away;   // a tie: the even one
}

namespace {
std::string decimal_text(double v, std::chars_format format, int precision) {
  char buf[400];   // (the longest: 309 integer digits, a sign, a point and the places)
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v, format, precision);
  return std::string(buf, r.ec == std::errc() ? r.ptr : buf);
}
}  // namespace

std::string fixed_text(double v, int places) { return decimal_text(v, std::chars_format::fixed, places); }
std::string general_text(double v, int digits) { return decimal_text(v, std::chars_format::general, digits); }

bool operator<(const Point2& a, const Point2& b) {
  int c = cmp(a.x, b.x);
  return c < 0 || (c == 0 && a.y < b.y);
}
bool operator==(const Point2& a, const Point2& b) { return a.x == b.x && a.y == b.y; }

const char* to_string(EdgeKind k) {
  switch (k) {
    case EdgeKind::Border: return "border";
    case EdgeKind::Silhouette: return "silhouette";
    case EdgeKind::Crease: return "crease";
    case EdgeKind::Smooth: return "smooth";
    case EdgeKind::Intersection: return "intersection";
  }
  return "?";
}

}  // namespace vismap
