#include "arrangements/rational.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "arrangements/visibility_map.h"

namespace vismap {

std::string canonical(const mpq_class& q) {
  mpq_class c(q);
  c.canonicalize();   // lowest terms, positive denominator; GMP prints "n" when den = 1
  return c.get_str();
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
