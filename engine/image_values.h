// The exact value of a vertex image's coordinate, as the canonical rational the
// map writes, made from the input doubles with machine integers: a row of the
// view applied to a vertex is a sum of products of doubles, an integer times a
// power of two that mostly fits in 128 bits; an orthographic coordinate is that
// (no gcd: its denominator is a power of two), a perspective one the quotient of
// two such (N / W: one gcd, of two odd integers). GMP and CGAL's Mpzf took the
// same values through binary floats, two rationals and a rational division (for
// a perspective coordinate about twice the instructions: 4.7 k against 2.4 k). Where a value
// does not fit (the products' exponents far apart) the caller takes that way.
#pragma once
#include <gmp.h>

#include <array>
#include <cstdint>

#include "engine/scene.h"

namespace vismap::exact {

__extension__ typedef __int128 Int128;

// m 2^e exactly: m odd (or 0, e then 0), |m| < 2^126.
struct Dyadic {
  Int128 m = 0;
  long e = 0;
};

// (row . (p, 1)) exactly as a Dyadic, or false where it does not fit.
bool row_dyadic(const std::array<double, 4>& row, const Vec3& p, Dyadic& out);

// The sign of the exact sum of four doubles, or false where it does not fit
// (their exponents far apart, or not finite).
bool sum_sign(const std::array<double, 4>& terms, int& sign);

// q = a 2^k, canonical (q initialised).
void set_dyadic(mpq_ptr q, const Dyadic& a, long k);

// q = n 2^k / w, canonical (q initialised; w != 0).
void set_quotient(mpq_ptr q, const Dyadic& n, const Dyadic& w, long k);

}  // namespace vismap::exact
