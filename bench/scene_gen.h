// Deterministic synthetic scenes for benchmarks and tests.
//
// Every generator is a pure function of its arguments: the seeded ones use the
// small PRNG below (SplitMix64 seeding xoshiro256**) and only +, -, *, / and
// sqrt, which IEEE 754 rounds exactly, so a seed gives bit-identical scenes on
// every compiler and standard library (CMakeLists.txt turns off FMA contraction,
// which would change roundings). sphere() alone uses sin/cos, whose last bit may
// differ between math libraries; it takes no seed.
//
// No CGAL and no vismap_core: only the header-only types of engine/scene.h.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/scene.h"

namespace vismap::gen {

// xoshiro256** seeded through SplitMix64 (Blackman & Vigna). Small, fast, and
// fully specified, unlike the std:: distributions.
class Rng {
 public:
  explicit Rng(std::uint64_t seed);
  std::uint64_t next();                   // 64 uniform bits
  double uniform();                       // [0, 1), multiples of 2^-53
  double uniform(double lo, double hi);   // [lo, hi)

 private:
  std::uint64_t s_[4];
};

// Franklin's hidden-surface test scene: n axis-aligned squares of side L in
// the plane z = const, lying fully inside [0,1]^2, at random depths z in [0,1),
// counter-clockwise seen from +z (front-facing for --dir 0,0,-1).
// Requires 0 < side <= 1.
Scene random_squares(std::size_t n, double side, std::uint64_t seed);

// The same, sized for a target depth complexity D = n * L^2 (L = sqrt(D / n)),
// so D stays constant while n grows. Requires 0 < D <= n.
Scene random_squares_depth(std::size_t n, double depth_complexity, std::uint64_t seed);

// General position: n equilateral triangles of circumdiameter `size`, random
// centre, random plane and random orientation, inside the unit cube.
// Each triangle has its own three vertices. Requires 0 < size <= 1.
Scene random_triangles(std::size_t n, double size, std::uint64_t seed);

// n triangles that share corners: each has one of `hubs` common corners (spread
// in the unit cube) and two corners of its own within 0.4 of it, so that many
// pairs cross each other's plane at the shared corner, some piercing each other
// from it and some meeting only there. Requires hubs >= 1.
Scene corner_fans(std::size_t n, int hubs, std::uint64_t seed);

// n plates with holes, interpenetrating: each a rectangle in a random plane
// spanned by two small integer vectors (so that every corner, a multiple of
// 1/64, lies exactly in it), with holes (triangles and quads, either turn) in
// some cells of a 4 x 4 grid over it and, sometimes, one more that shares the
// rectangle's corner. Exactly planar, holes inside and apart: what Scene allows.
Scene holed_plates(std::size_t n, std::uint64_t seed);

// Appends a closed, outward-oriented box from lo to hi (8 vertices, 6 quads).
void add_box(Scene& s, Vec3 lo, Vec3 hi);

// Franklin's cubical array: k^3 closed, outward-oriented unit cubes (8 shared
// vertices, 6 quads each) at pitch 1 + gap, so neighbours never touch.
// Many exactly parallel edges and faces; exercises occlusion culling.
Scene cube_array(int k, double gap = 0.5);

// A closed, outward-oriented UV sphere: nu >= 3 slices around the z axis,
// nv >= 2 stacks pole to pole; quads between stacks, triangles at the poles,
// shared vertices. Quads are planar only up to rounding: expect fan splits.
Scene sphere(int nu, int nv, double radius = 1.0, Vec3 center = {});

// n closed, outward-oriented axis-aligned boxes, each long along one axis
// (cycling x, y, z) and all crossing the cube's centre region, so their
// surfaces pierce each other: exercises intersection lines.
Scene interpenetrating_boxes(std::size_t n, std::uint64_t seed);

// A k x k height field over [0,1]^2: (k+1)^2 shared vertices, two triangles
// per cell (so every face is exactly planar), upward-facing, smooth
// multi-octave value-noise heights of amplitude about 0.2. Exercises smooth
// edges, creases and self-occlusion of one connected surface.
Scene terrain(int k, std::uint64_t seed);

// Appends `src` to `dst`: vertices after dst's, faces after dst's with their
// indices offset, so face numbers of `src` shift by dst's old face count.
void append_scene(Scene& dst, const Scene& src);

// p -> p * scale + offset for every vertex (e.g. to test huge or tiny scenes).
void transform(Scene& scene, double scale, Vec3 offset = {});

// The scene as OFF text, coordinates in shortest round-trip form, so reading
// it back gives exactly the same doubles (lets the CLI run generated scenes).
std::string to_off(const Scene& scene);

}  // namespace vismap::gen
