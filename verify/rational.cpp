#include "verify/rational.h"

namespace vismap_check {
namespace {

bool digits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  return true;
}

}  // namespace

bool parse_canonical(std::string_view s, mpq_class& out, std::string& why) {
  std::string_view body = s;
  bool negative = !body.empty() && body[0] == '-';
  if (negative) body.remove_prefix(1);
  std::size_t slash = body.find('/');
  std::string_view num = body.substr(0, slash);
  std::string_view den = slash == std::string_view::npos ? std::string_view() : body.substr(slash + 1);
  if (!digits(num) || (slash != std::string_view::npos && !digits(den))) {
    why = "not a rational of the form [-]N or [-]N/D";
    return false;
  }
  if (num.size() > 1 && num[0] == '0') { why = "leading zero"; return false; }
  if (!den.empty() && den[0] == '0') { why = "leading zero or zero denominator"; return false; }
  mpz_class n(std::string(num), 10);
  if (negative && n == 0) { why = "\"-0\""; return false; }
  if (slash != std::string_view::npos) {
    mpz_class d(std::string(den), 10);
    if (d == 1) { why = "denominator 1 written"; return false; }
    mpz_class g;
    mpz_gcd(g.get_mpz_t(), n.get_mpz_t(), d.get_mpz_t());
    if (g != 1) { why = "not in lowest terms"; return false; }
    out = mpq_class(n, d);
  } else {
    out = mpq_class(n);
  }
  if (negative) out = -out;
  return true;
}

std::string str(const mpq_class& q) { return q.get_str(); }

}  // namespace vismap_check
