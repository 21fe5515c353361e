// The one place that names the exact kernel. Only the CGAL translation units of
// the engine include this; public headers stay free of CGAL.
#pragma once
#ifndef VISMAP_EXACT_CONFIG_H
#error "engine/exact_config.h must come first (CMake force-includes it for vismap_core)"
#endif
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <gmpxx.h>

namespace vismap::exact {

using K = CGAL::Epeck;          // filtered predicates, lazy exact constructions
using FT = K::FT;
using P2 = K::Point_2;
using V2 = K::Vector_2;
using Seg2 = K::Segment_2;

// The exact value of a kernel number as a GMP rational (forces exact evaluation).
// (CGAL picks mpq_class or Boost's gmp_rational depending on what is included.)
inline mpq_class to_mpq(const mpq_class& q) { return q; }
template <class Boost_rational>
mpq_class to_mpq(const Boost_rational& q) { return mpq_class(q.backend().data()); }
inline mpq_class to_mpq(const FT& x) { return to_mpq(CGAL::exact(x)); }

// Screen-space point with its depth: (x, y) on the screen, z = depth (smaller = nearer).
// The point (x, y) is built once: each lazy point made costs an allocation.
struct P3 {
  FT x, y, z;
  P2 p;
  P3() = default;
  P3(const FT& x_, const FT& y_, const FT& z_) : x(x_), y(y_), z(z_), p(x_, y_) {}
  P3(const P2& q, const FT& z_) : x(q.x()), y(q.y()), z(z_), p(q) {}
  const P2& xy() const { return p; }
};

}  // namespace vismap::exact
