#include "engine/image_values.h"

#include <algorithm>
#include <bit>
#include <numeric>

namespace vismap::exact {
namespace {

__extension__ typedef unsigned __int128 UInt128;
static_assert(GMP_LIMB_BITS == 64, "two limbs hold 128 bits");

// A finite double as m 2^e, m an odd integer of at most 53 bits (or 0); false
// for infinities and NaN.
bool split(double d, std::int64_t& m, long& e) {
  const auto bits = std::bit_cast<std::uint64_t>(d);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  if (biased == 0x7ff) return false;
  std::uint64_t mantissa = bits & ((std::uint64_t{1} << 52) - 1);
  e = biased == 0 ? -1074 : biased - 1075;   // (subnormals: no hidden bit)
  if (biased != 0) mantissa |= std::uint64_t{1} << 52;
  if (mantissa == 0) {
    m = 0, e = 0;
    return true;
  }
  const int zeros = std::countr_zero(mantissa);
  mantissa >>= zeros;
  e += zeros;
  m = bits >> 63 ? -static_cast<std::int64_t>(mantissa) : static_cast<std::int64_t>(mantissa);
  return true;
}

UInt128 magnitude(Int128 m) { return m < 0 ? -static_cast<UInt128>(m) : static_cast<UInt128>(m); }

int bit_length(UInt128 v) {
  const auto hi = static_cast<std::uint64_t>(v >> 64), lo = static_cast<std::uint64_t>(v);
  return hi ? 128 - std::countl_zero(hi) : 64 - std::countl_zero(lo);
}

int trailing_zeros(UInt128 v) {   // (v != 0)
  const auto lo = static_cast<std::uint64_t>(v);
  return lo ? std::countr_zero(lo) : 64 + std::countr_zero(static_cast<std::uint64_t>(v >> 64));
}

// z = v (a GMP integer from 128 bits, no allocation beyond z's two limbs).
void set_magnitude(mpz_ptr z, UInt128 v) {
  mp_limb_t* limbs = mpz_limbs_write(z, 2);
  limbs[0] = static_cast<mp_limb_t>(v);
  limbs[1] = static_cast<mp_limb_t>(v >> 64);
  mpz_limbs_finish(z, limbs[1] ? 2 : limbs[0] ? 1 : 0);
}

// gcd of two odd numbers: on one limb each, the binary algorithm of the
// standard library; else GMP's mpn_gcd on copies (it destroys its operands,
// wants the first at least as long and one of them odd).
UInt128 gcd_of_odd(UInt128 a, UInt128 b) {
  if ((a >> 64) == 0 && (b >> 64) == 0) return std::gcd(static_cast<std::uint64_t>(a), static_cast<std::uint64_t>(b));
  if (bit_length(a) < bit_length(b)) std::swap(a, b);
  mp_limb_t x[2] = {static_cast<mp_limb_t>(a), static_cast<mp_limb_t>(a >> 64)};
  mp_limb_t y[2] = {static_cast<mp_limb_t>(b), static_cast<mp_limb_t>(b >> 64)};
  mp_limb_t g[2] = {0, 0};
  mpn_gcd(g, x, 2, y, y[1] ? 2 : 1);
  return (static_cast<UInt128>(g[1]) << 64) | g[0];
}

// q = sign * num 2^e / den, num and den odd and coprime: canonical.
void set_canonical(mpq_ptr q, bool negative, UInt128 num, UInt128 den, long e) {
  set_magnitude(mpq_numref(q), num);
  set_magnitude(mpq_denref(q), den);
  if (e > 0) mpz_mul_2exp(mpq_numref(q), mpq_numref(q), static_cast<mp_bitcnt_t>(e));
  if (e < 0) mpz_mul_2exp(mpq_denref(q), mpq_denref(q), static_cast<mp_bitcnt_t>(-e));
  if (negative) mpz_neg(mpq_numref(q), mpq_numref(q));
}

// m 2^e: a double, or the product of two (|m| < 2^106).
struct Term {
  Int128 m;
  long e;
};

// The sum of n terms as sum 2^least (least: their least exponent; 0 for no
// term), or false where a term over that exponent needs more than 124 bits:
// four of them then sum in 126.
bool sum_of(const Term* terms, int n, Int128& sum, long& least) {
  sum = 0;
  least = 0;
  if (n == 0) return true;
  least = terms[0].e;
  for (int i = 1; i < n; ++i) least = std::min(least, terms[i].e);
  for (int i = 0; i < n; ++i) {
    const long shift = terms[i].e - least;
    if (shift + bit_length(magnitude(terms[i].m)) > 124) return false;
    sum += terms[i].m * (static_cast<Int128>(1) << shift);
  }
  return true;
}

}  // namespace

bool row_dyadic(const std::array<double, 4>& row, const Vec3& p, Dyadic& out) {
  Term terms[4];
  int n = 0;
  const double v[3] = {p.x, p.y, p.z};
  for (std::size_t c = 0; c < 4; ++c) {
    std::int64_t a = 1, b = 1;
    long ea = 0, eb = 0;
    if (!split(row[c], a, ea) || (c < 3 && !split(v[c], b, eb))) return false;
    if (a != 0 && b != 0) terms[n++] = Term{static_cast<Int128>(a) * b, ea + eb};   // (|m| < 2^106)
  }
  Int128 sum = 0;
  long least = 0;
  if (!sum_of(terms, n, sum, least)) return false;
  out = Dyadic{};
  if (sum == 0) return true;
  const int zeros = trailing_zeros(magnitude(sum));
  out = Dyadic{sum / (static_cast<Int128>(1) << zeros), least + zeros};
  return true;
}

bool sum_sign(const std::array<double, 4>& values, int& sign) {
  Term terms[4];
  int n = 0;
  for (const double v : values) {
    std::int64_t m = 0;
    long e = 0;
    if (!split(v, m, e)) return false;
    if (m != 0) terms[n++] = Term{m, e};
  }
  Int128 sum = 0;
  long least = 0;
  if (!sum_of(terms, n, sum, least)) return false;
  sign = (sum > 0) - (sum < 0);
  return true;
}

void set_dyadic(mpq_ptr q, const Dyadic& a, long k) {
  if (a.m == 0) return mpq_set_ui(q, 0, 1);
  set_canonical(q, a.m < 0, magnitude(a.m), 1, a.e + k);
}

void set_quotient(mpq_ptr q, const Dyadic& n, const Dyadic& w, long k) {
  if (n.m == 0) return mpq_set_ui(q, 0, 1);
  UInt128 a = magnitude(n.m), b = magnitude(w.m);
  if (const UInt128 g = gcd_of_odd(a, b); g != 1) a /= g, b /= g;
  set_canonical(q, (n.m < 0) != (w.m < 0), a, b, n.e - w.e + k);
}

}  // namespace vismap::exact
