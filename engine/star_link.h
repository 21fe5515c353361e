// Whether the triangles around a vertex tile a disk in some plane: the test
// EmbeddedStars (on the screen) and the self-contact test (along an axis) make
// of a vertex's star. Internal to the engine.
#pragma once
#include <cstddef>

namespace vismap::engine {

// The most triangles a star may have to be told (rare on meshes beyond; a
// fan's hub is a polygon's).
constexpr std::size_t kMaxStar = 32;

// Whether the link edges from(i) -> to(i), i < n, of the triangles (v, from(i),
// to(i)), each turning positively about v in the plane, make one closed cycle
// that goes round v once; below(i) tells whether from(i) lies on or below v's
// horizontal line. One cycle: following each edge by the one that starts where
// it ends, from the first, comes back to it after all n (then no two start at
// one link vertex: both would follow the same edge). Once round: every
// triangle turns positively, so the winding number is the number of link edges
// crossing v's line upwards (each such crossing lies right of v; the half-open
// rule counts a link vertex on the line once).
template <class From, class To, class Below>
bool goes_round_once(std::size_t n, From&& from, To&& to, Below&& below) {
  if (n < 3 || n > kMaxStar) return false;
  std::size_t next[kMaxStar];
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t j = 0;
    while (j < n && from(j) != to(i)) ++j;
    if (j == n) return false;
    next[i] = j;
  }
  std::size_t at = 0;
  for (std::size_t steps = 1; steps < n; ++steps) {
    at = next[at];
    if (at == 0) return false;
  }
  if (next[at] != 0) return false;
  bool low[kMaxStar];
  for (std::size_t i = 0; i < n; ++i) low[i] = below(i);
  int upward = 0;
  for (std::size_t i = 0; i < n; ++i) upward += low[i] && !low[next[i]];
  return upward == 1;
}

}  // namespace vismap::engine
