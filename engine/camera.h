// Camera: how the scene is looked at. The view matrix is built in doubles, and
// those doubles are then the exact matrix (see docs/format.md).
#pragma once
#include <array>
#include <optional>

#include "engine/scene.h"

namespace vismap {

// Row-major 4x4 of doubles; every entry is taken as an exact rational.
// World (x,y,z,1) -> (X,Y,Z,W); screen (X/W, Y/W), depth Z/W (smaller = nearer).
// Perspective: the near plane is depth 0; only points with W > 0 and Z > 0 are kept.
struct View {
  bool perspective = false;
  std::array<std::array<double, 4>, 4> m{};
  Vec3 eye{};   // perspective only: the eye point (W = 0 there)
};

// Throws std::invalid_argument for an impossible camera (zero direction, eye on
// target, fov outside (0,180)). With nothing given: the whole scene, seen obliquely.
View make_view(const Camera& spec, const Scene& scene);

}  // namespace vismap
