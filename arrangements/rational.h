// Exact rationals as text, "0", "-3", "7/16" (lowest terms, no "3/1", no "-0"),
// and as the nearest double.
#pragma once
#include <gmpxx.h>

#include <string>

namespace vismap {

std::string canonical(const mpq_class& q);
// canonical(q) appended to out.
void append_canonical(std::string& out, const mpq_class& q);
// The same text for a q already in lowest terms with a positive denominator, as
// GMP keeps every value its arithmetic makes (and requires of its operands):
// no gcd to check it, where append_canonical takes one for every number that
// is not a fraction over a power of two (a perspective map's are not: ~30 % of
// a 10^6-triangle terrain's JSON writing). Checked where assertions are on.
void append_lowest_terms(std::string& out, const mpq_class& q);
// Whether q is so (a gcd): append_lowest_terms' precondition.
bool in_lowest_terms(const mpq_class& q);

// The double nearest to q (ties to even; subnormals and overflow to infinity as
// IEEE rounding gives them). GMP's own mpq_get_d truncates.
double nearest_double(const mpq_class& q);

// A double as decimal text, as printf writes it with "%.<places>f" (fixed) and
// "%.<digits>g" (general) in the C locale: std::to_chars, which is specified to
// give that text, without printf's format parsing (a drawing writes hundreds of
// thousands of coordinates: snprintf was 8% of a lines-only drawing's time).
std::string fixed_text(double v, int places);
std::string general_text(double v, int digits);

}  // namespace vismap
