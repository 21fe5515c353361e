// Image-precision baselines: the classic hidden-surface algorithms that answer
// "which face is seen at this pixel centre?" in plain doubles, for comparing run
// time and error against the exact engine (issue 4).
//
//   project()   scene + View (engine/camera.h) -> screen pieces: convex polygons,
//               counter-clockwise on the screen, each with its face index and its
//               depth plane depth = a*x + b*y + c (doubles; near-plane clipped)
//   zbuffer()   Catmull's depth buffer, one span per piece and row
//   scanline()  Watkins-style scan line: edge table, active edge list sorted by x,
//               IN flags per piece, depth compared only where pieces overlap
//   warnock()   Warnock's area subdivision (enclosing / involved / out), down to
//               the pixel
//   raycast()   one ray per pixel centre through a uniform screen grid whose cells
//               list their pieces front to back (early exit)
//
// Every method labels the pixel CENTRE with an input face index (-1: background),
// the visible face being the smallest in the order (depth, face index), as in the
// exact engine: nearest depth, and on equal depth (coplanar overlap) the lowest
// index. Depths are doubles here, so "equal" is bitwise equality of the two plane
// evaluations: exact for faces parallel to the screen, a matter of rounding for
// tilted coplanar faces.
//
// No CGAL and no GMP: this library depends only on engine/scene.h and
// engine/camera.h (View is a plain struct; make_view lives in the core).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/camera.h"
#include "engine/scene.h"

namespace vismap::raster {

// A convex screen polygon cut from one face: vertices first..first+count-1 of
// ScreenScene::x/y, counter-clockwise (back faces are reversed: faces are
// two-sided, as in the exact engine), with the face's depth plane.
struct Piece {
  int face = -1;
  std::uint32_t first = 0, count = 0;
  double a = 0, b = 0, c = 0;                  // depth(x, y) = a*x + (b*y + c)
  double xmin = 0, xmax = 0, ymin = 0, ymax = 0;
  double dmin = 0, dmax = 0;                   // depth range over the vertices
  // Every method evaluates depth with this one expression (rows first: b*y + c
  // is constant along a row), so that equal planes give bitwise equal depths.
  double depth(double x, double y) const { return a * x + (b * y + c); }
};

struct ScreenScene {
  std::vector<Piece> pieces;   // in ascending face order
  std::vector<double> x, y;    // piece vertices
  // Inside test of piece p: for each edge k, ex[k]*x + ey[k]*y + e0[k] >= 0
  // (edge k runs from vertex k to vertex k+1, the inside is on its left).
  std::vector<double> ex, ey, e0;
  double xmin = 0, xmax = 0, ymin = 0, ymax = 0;   // of all pieces (0 when empty)
  std::size_t faces = 0;                           // faces in the scene
  std::size_t faces_drawn = 0;                     // faces with at least one piece

  bool inside(const Piece& p, double px, double py) const {
    for (std::uint32_t k = p.first; k < p.first + p.count; ++k)
      if (ex[k] * px + ey[k] * py + e0[k] < 0) return false;
    return true;
  }
};

// The scene in screen space, in doubles, with the engine's conventions
// (docs/format.md, perspective): (X, Y, Z, W) = view.m * (x, y, z, 1); a perspective
// view keeps Z >= 0 (the near plane; polygons are clipped there in homogeneous
// coordinates) and divides: screen (X/W, Y/W), depth Z/W, which is affine over
// the screen image of a plane, so one depth plane per piece is exact up to
// rounding. Polygons: consecutive repeated vertices dropped; fewer than 3, or no
// area on the screen (edge-on, |area| <= 1e-14 * bbox extent^2) -> no piece;
// triangles and convex planar polygons -> one piece; non-convex planar polygons
// -> ear clipping in the polygon's plane (in doubles; a polygon ear clipping
// cannot finish, self-intersecting, falls back to the fan from its first vertex,
// like the engine); non-planar polygons (a vertex off the Newell plane by more
// than 1e-9 of the polygon's size) -> the fan from the first vertex, like the
// engine; polygons planar only up to rounding (sphere quads) stay one piece.
ScreenScene project(const Scene& scene, const View& view);

// The pixel grid: R x R square pixels of side `pixel`; pixel (i, j) has its
// centre at (cx(i), cy(j)); row j = 0 is the bottom (screen y grows upwards).
// Every method and the exact labels use these same double centres.
struct Window {
  int R = 0;
  double x0 = 0, y0 = 0, pixel = 1;
  double cx(int i) const { return x0 + (i + 0.5) * pixel; }
  double cy(int j) const { return y0 + (j + 0.5) * pixel; }
};

// The square window centred on the box [xmin, xmax] x [ymin, ymax], side the
// larger extent (1 if the box is empty or a point), split into R x R pixels.
Window window_for_box(double xmin, double xmax, double ymin, double ymax, int R);
// ... on the scene's screen box, which is the exact map's extent up to rounding
// (the map covers exactly the union of the projected faces that are not edge-on).
Window window_for(const ScreenScene& s, int R);

// Face labels, row-major: label[j * R + i] is pixel (i, j).
struct Image {
  int R = 0;
  std::vector<std::int32_t> label;
  std::int32_t at(int i, int j) const { return label[static_cast<std::size_t>(j) * R + i]; }
};

Image zbuffer(const ScreenScene& s, const Window& w);
Image scanline(const ScreenScene& s, const Window& w);
Image warnock(const ScreenScene& s, const Window& w);
Image raycast(const ScreenScene& s, const Window& w);

// The four methods by name, for benchmarks and tests.
enum class Method { ZBuffer, ScanLine, Warnock, RayCast };
inline constexpr Method kMethods[] = {Method::ZBuffer, Method::ScanLine, Method::Warnock, Method::RayCast};
const char* name(Method m);
Image render(Method m, const ScreenScene& s, const Window& w);

// How a label image becomes a line drawing: the usual edge detection on face-id,
// depth and normal buffers. A label change between neighbouring pixels showing
// faces f and g is a line unless f and g lie on one smooth patch and the depth
// is continuous there:
//   - smooth patch: the connected components of "shares a mesh vertex (by
//     index) with, faces the same way as, and has a normal within crease_deg
//     of"; faces that share a vertex but not smoothly (a crease, a silhouette)
//     always get a line between them, as in the exact drawing;
//   - depth continuous at the midpoint m between the two pixel centres:
//     |depth_f(m) - depth_g(m)| <= 2 * pixel * (|grad depth_f| + |grad depth_g|)
//     (a smooth surface seen across a pixel, not a fold of it hiding another
//     part of itself), with each face's depth plane from its screen piece.
// So a mesh finer than the pixels (a sphere's poles and rim) draws only its
// outline, as the exact engine does with smooth edges off, while separate
// objects, creases and self-occlusion stay lines. Decided in doubles.
struct LineRule {
  std::vector<std::int32_t> patch;         // per face: its smooth patch
  std::vector<std::uint64_t> creases;      // sorted keys (min << 32 | max): vertex-sharing, not smooth
  std::vector<double> a, b, c, grad;       // per face: depth plane, |gradient|
  bool drawn(std::int32_t f, std::int32_t g, double x, double y, double pixel) const;
};
LineRule line_rule(const Scene& scene, const View& view, const ScreenScene& s, double crease_deg = 30);
// Every label change is a line (for tests).
LineRule all_changes();

}  // namespace vismap::raster
