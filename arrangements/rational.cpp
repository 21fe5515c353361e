#include "arrangements/rational.h"

#include "arrangements/visibility_map.h"

namespace vismap {

std::string canonical(const mpq_class& q) {
  mpq_class c(q);
  c.canonicalize();   // lowest terms, positive denominator; GMP prints "n" when den = 1
  return c.get_str();
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
