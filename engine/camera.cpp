// Builds the view matrix in doubles, exactly as the spec prescribes; from then on
// the doubles are exact rationals and no rounding happens anywhere in the engine.
#include "engine/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace vismap {
namespace {

Vec3 sub(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 scale(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
bool finite(Vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

// a times the power of two that brings its largest component into [1, 2): exact,
// so every formula below gives the same doubles on it as on a, except that its
// squares neither overflow (coordinates near 1e300) nor underflow (near 1e-300).
Vec3 balanced(Vec3 a) {
  const double m = std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)});
  if (m == 0 || !std::isfinite(m)) return a;
  const int e = std::ilogb(m);
  return {std::ldexp(a.x, -e), std::ldexp(a.y, -e), std::ldexp(a.z, -e)};
}

// |a|, without overflow or underflow in the squares (the same double as
// sqrt(a.a) wherever that neither overflows nor underflows).
double norm(Vec3 a) {
  const double m = std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)});
  if (m == 0 || !std::isfinite(m)) return m;
  const Vec3 b = balanced(a);
  return std::ldexp(std::sqrt(dot(b, b)), std::ilogb(m));
}

struct Frame {
  Vec3 r, u, f;  // right, up, forward (unit, in doubles)
};

// r = (d x up)/|d x up|, u = (r x d)/|r x d|, f = d/|d|; up defaults to +z, or +y
// when +z is parallel to d.
Frame make_frame(Vec3 d, std::optional<Vec3> up_opt) {
  if (!finite(d) || norm(d) == 0) throw std::invalid_argument("view direction must be a non-zero finite vector");
  d = balanced(d);   // (the same frame; no overflow for an eye at 1e300)
  Vec3 up = balanced(up_opt.value_or(Vec3{0, 0, 1}));
  Vec3 ru = cross(d, up);
  if (norm(ru) == 0) {
    if (up_opt) throw std::invalid_argument("the up direction is parallel to the view direction");
    up = Vec3{0, 1, 0};
    ru = cross(d, up);
  }
  Frame fr;
  fr.r = scale(ru, 1 / norm(ru));
  Vec3 uu = cross(fr.r, d);
  fr.u = scale(uu, 1 / norm(uu));
  fr.f = scale(d, 1 / norm(d));
  return fr;
}

struct Box {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi{-lo.x, -lo.y, -lo.z};
  bool empty() const { return lo.x > hi.x; }
};

Box scene_box(const Scene& s) {
  Box b;
  for (const auto& f : s.faces)
    for (auto i : f) {
      const Vec3& p = s.vertices[i];
      b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y), std::min(b.lo.z, p.z)};
      b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y), std::max(b.hi.z, p.z)};
    }
  if (b.empty()) b.lo = b.hi = Vec3{0, 0, 0};
  return b;
}

}  // namespace

View make_view(const Camera& spec, const Scene& scene) {
  View v;
  const bool persp = spec.eye || spec.target || spec.fov_deg;
  if (persp && spec.dir) throw std::invalid_argument("an orthographic direction cannot be combined with a perspective eye, target or field of view");
  if (!persp) {
    // Orthographic; the default looks obliquely down at the scene.
    Vec3 d = spec.dir.value_or(Vec3{-1, -2, -1.5});
    Frame fr = make_frame(d, spec.up);
    v.perspective = false;
    v.m = {{{fr.r.x, fr.r.y, fr.r.z, 0}, {fr.u.x, fr.u.y, fr.u.z, 0}, {fr.f.x, fr.f.y, fr.f.z, 0}, {0, 0, 0, 1}}};
    return v;
  }
  Box b = scene_box(scene);
  Vec3 center{(b.lo.x + b.hi.x) / 2, (b.lo.y + b.hi.y) / 2, (b.lo.z + b.hi.z) / 2};
  double radius = std::max(norm(sub(b.hi, b.lo)) / 2, 1e-300);
  double fov = spec.fov_deg.value_or(40);
  if (!(fov > 0 && fov < 180)) throw std::invalid_argument("the field of view must be between 0 and 180 degrees");
  Vec3 target = spec.target.value_or(center);
  double t = std::tan(fov * M_PI / 360);
  // Without --eye, back off along the default direction until the scene fits.
  Vec3 eye = spec.eye.value_or(
      sub(target, scale(Vec3{-1, -2, -1.5}, (radius / std::sin(fov * M_PI / 360) + radius) / norm(Vec3{-1, -2, -1.5}))));
  if (!finite(eye) || !finite(target)) throw std::invalid_argument("the eye and the target must be finite");
  Vec3 d = sub(target, eye);
  if (norm(d) == 0) throw std::invalid_argument("the eye and the target must differ");
  Frame fr = make_frame(d, spec.up);
  // Near plane: a small fraction of the eye-target distance, so that only what is
  // (almost) at the eye is clipped. depth = (fz - near)/fz with fz = f.(p - eye).
  double near = norm(d) * 1e-3;
  double ex = -dot(fr.r, eye) / t, ey = -dot(fr.u, eye) / t, ef = -dot(fr.f, eye);
  v.perspective = true;
  v.eye = eye;
  // Far from the origin (an eye at 1e15) ef - near can round back to ef: the
  // near plane would pass through the eye and every depth Z/W would be 1. The
  // next double below ef then gives the nearest near plane the doubles allow.
  double ez = ef - near;
  if (!(ez < ef)) ez = std::nextafter(ef, -HUGE_VAL);
  v.m = {{{fr.r.x / t, fr.r.y / t, fr.r.z / t, ex},
          {fr.u.x / t, fr.u.y / t, fr.u.z / t, ey},
          {fr.f.x, fr.f.y, fr.f.z, ez},
          {fr.f.x, fr.f.y, fr.f.z, ef}}};
  for (const auto& row : v.m)
    for (double x : row)
      if (!std::isfinite(x))
        throw std::invalid_argument("the perspective view matrix overflows doubles (the eye too far from the origin)");
  return v;
}

}  // namespace vismap
