// Scene + View -> convex screen pieces with depth planes, in doubles
// (see raster.h for the conventions). Mirrors the engine's world_facets and
// screen_scene stages, without exactness: fan / ear clipping in the polygon's
// plane, near-plane clipping in homogeneous coordinates, then the division.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "bench/raster/raster.h"

namespace vismap::raster {
namespace {

struct H4 {
  double X, Y, Z, W;
};

Vec3 sub(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

Vec3 newell_normal(const std::vector<Vec3>& p) {
  Vec3 n;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 &a = p[i], &b = p[(i + 1) % p.size()];
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  return n;
}

// 2D coordinates of a planar polygon in the plane of its dominant normal axis,
// oriented so that the polygon runs counter-clockwise there.
struct Flat {
  std::vector<double> u, v;
};
Flat flatten(const std::vector<Vec3>& p, Vec3 n) {
  const double ax = std::abs(n.x), ay = std::abs(n.y), az = std::abs(n.z);
  Flat f;
  f.u.reserve(p.size());
  f.v.reserve(p.size());
  for (const Vec3& q : p) {
    if (az >= ax && az >= ay) {
      f.u.push_back(q.x);
      f.v.push_back(n.z > 0 ? q.y : -q.y);
    } else if (ax >= ay) {
      f.u.push_back(q.y);
      f.v.push_back(n.x > 0 ? q.z : -q.z);
    } else {
      f.u.push_back(q.z);
      f.v.push_back(n.y > 0 ? q.x : -q.x);
    }
  }
  return f;
}

double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// Convex (and winding once) in the flat, counter-clockwise coordinates: every
// turn is left or straight, and u changes direction at most twice.
bool convex(const Flat& f) {
  const std::size_t n = f.u.size();
  int changes = 0, last = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n, k = (i + 2) % n;
    if (cross2(f.u[j] - f.u[i], f.v[j] - f.v[i], f.u[k] - f.u[j], f.v[k] - f.v[j]) < 0) return false;
    const double du = f.u[j] - f.u[i];
    const int s = du > 0 ? 1 : du < 0 ? -1 : 0;
    if (s != 0) {
      if (last != 0 && s != last) ++changes;
      last = s;
    }
  }
  return changes <= 2;
}

// Ear clipping in the flat coordinates; false if no ear can be found (the
// polygon is self-intersecting), leaving `tris` unspecified.
bool ear_clip(const Flat& f, std::vector<std::vector<int>>& tris) {
  std::vector<int> idx(f.u.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<int>(i);
  auto turn = [&](int a, int b, int c) {
    return cross2(f.u[b] - f.u[a], f.v[b] - f.v[a], f.u[c] - f.u[a], f.v[c] - f.v[a]);
  };
  while (idx.size() > 3) {
    bool found = false;
    const std::size_t n = idx.size();
    for (std::size_t i = 0; i < n && !found; ++i) {
      const int a = idx[(i + n - 1) % n], b = idx[i], c = idx[(i + 1) % n];
      if (turn(a, b, c) <= 0) continue;   // reflex or flat: not an ear
      bool empty = true;
      for (int q : idx) {
        if (q == a || q == b || q == c) continue;
        if ((f.u[q] == f.u[a] && f.v[q] == f.v[a]) || (f.u[q] == f.u[b] && f.v[q] == f.v[b]) ||
            (f.u[q] == f.u[c] && f.v[q] == f.v[c]))
          continue;
        if (turn(a, b, q) >= 0 && turn(b, c, q) >= 0 && turn(c, a, q) >= 0) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      tris.push_back({a, b, c});
      idx.erase(idx.begin() + static_cast<std::ptrdiff_t>(i));
      found = true;
    }
    if (!found) return false;
  }
  tris.push_back(idx);
  return true;
}

// The polygon's world-space pieces, as lists of indices into p.
std::vector<std::vector<int>> world_pieces(const std::vector<Vec3>& p, Vec3 n) {
  const int m = static_cast<int>(p.size());
  std::vector<std::vector<int>> out;
  auto fan = [&] {
    out.clear();
    for (int k = 1; k + 1 < m; ++k) out.push_back({0, k, k + 1});
  };
  if (m == 3) {
    out.push_back({0, 1, 2});
    return out;
  }
  // Planar? Distance of every vertex from the Newell plane through p[0].
  double size = 0;
  for (const Vec3& q : p) {
    const Vec3 d = sub(q, p[0]);
    size = std::max({size, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
  }
  const double nn = std::sqrt(dot(n, n));
  double dev = 0;
  for (const Vec3& q : p) dev = std::max(dev, std::abs(dot(n, sub(q, p[0]))) / nn);
  if (dev > 1e-9 * size) {
    fan();
    return out;
  }
  const Flat f = flatten(p, n);
  if (convex(f)) {
    std::vector<int> all(p.size());
    for (int k = 0; k < m; ++k) all[k] = k;
    out.push_back(std::move(all));
    return out;
  }
  if (!ear_clip(f, out)) fan();
  return out;
}

// Keeps Z >= 0 (the kept side of the near plane), Sutherland-Hodgman.
std::vector<H4> clip_near(const std::vector<H4>& in) {
  std::vector<H4> out;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const H4 &a = in[i], &b = in[(i + 1) % in.size()];
    const bool ka = a.Z >= 0, kb = b.Z >= 0;
    if (ka) out.push_back(a);
    if (ka != kb) {
      const double t = a.Z / (a.Z - b.Z);
      out.push_back({a.X + t * (b.X - a.X), a.Y + t * (b.Y - a.Y), 0.0, a.W + t * (b.W - a.W)});
    }
  }
  return out;
}

void emit(ScreenScene& s, int face, const std::vector<H4>& hv, bool perspective) {
  std::vector<double> x, y, d;
  for (const H4& h : hv) {
    double px = h.X, py = h.Y, pd = h.Z;
    if (perspective) {
      if (!(h.W > 0)) return;
      px /= h.W;
      py /= h.W;
      pd /= h.W;
    }
    if (!x.empty() && px == x.back() && py == y.back()) continue;
    x.push_back(px);
    y.push_back(py);
    d.push_back(pd);
  }
  while (x.size() > 1 && x.front() == x.back() && y.front() == y.back()) {
    x.pop_back();
    y.pop_back();
    d.pop_back();
  }
  const std::size_t n = x.size();
  if (n < 3) return;
  double xmin = x[0], xmax = x[0], ymin = y[0], ymax = y[0];
  double area2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    xmin = std::min(xmin, x[i]);
    xmax = std::max(xmax, x[i]);
    ymin = std::min(ymin, y[i]);
    ymax = std::max(ymax, y[i]);
    const std::size_t j = (i + 1) % n;
    area2 += (x[i] - x[0]) * (y[j] - y[0]) - (x[j] - x[0]) * (y[i] - y[0]);
  }
  const double ext = std::max(xmax - xmin, ymax - ymin);
  if (!std::isfinite(area2) || std::abs(area2) <= 1e-14 * ext * ext) return;   // edge-on
  if (area2 < 0) {
    std::reverse(x.begin(), x.end());
    std::reverse(y.begin(), y.end());
    std::reverse(d.begin(), d.end());
  }
  // Depth plane through vertex 0 and the edge (k, k+1) making the largest triangle.
  std::size_t best = 1;
  double best_den = 0;
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double den = (x[k] - x[0]) * (y[k + 1] - y[0]) - (x[k + 1] - x[0]) * (y[k] - y[0]);
    if (den > best_den) {
      best_den = den;
      best = k;
    }
  }
  if (!(best_den > 0)) return;
  const double x1 = x[best] - x[0], y1 = y[best] - y[0], d1 = d[best] - d[0];
  const double x2 = x[best + 1] - x[0], y2 = y[best + 1] - y[0], d2 = d[best + 1] - d[0];
  Piece p;
  p.face = face;
  p.a = (d1 * y2 - d2 * y1) / best_den;
  p.b = (x1 * d2 - x2 * d1) / best_den;
  p.c = d[0] - p.a * x[0] - p.b * y[0];
  p.first = static_cast<std::uint32_t>(s.x.size());
  p.count = static_cast<std::uint32_t>(n);
  p.xmin = xmin;
  p.xmax = xmax;
  p.ymin = ymin;
  p.ymax = ymax;
  p.dmin = std::numeric_limits<double>::infinity();
  p.dmax = -p.dmin;
  for (std::size_t i = 0; i < n; ++i) {
    const double pd = p.depth(x[i], y[i]);
    p.dmin = std::min(p.dmin, pd);
    p.dmax = std::max(p.dmax, pd);
    const std::size_t j = (i + 1) % n;
    const double dx = x[j] - x[i], dy = y[j] - y[i];
    s.x.push_back(x[i]);
    s.y.push_back(y[i]);
    s.ex.push_back(-dy);
    s.ey.push_back(dx);
    s.e0.push_back(dy * x[i] - dx * y[i]);
  }
  if (s.pieces.empty()) {
    s.xmin = xmin;
    s.xmax = xmax;
    s.ymin = ymin;
    s.ymax = ymax;
  } else {
    s.xmin = std::min(s.xmin, xmin);
    s.xmax = std::max(s.xmax, xmax);
    s.ymin = std::min(s.ymin, ymin);
    s.ymax = std::max(s.ymax, ymax);
  }
  s.pieces.push_back(p);
}

}  // namespace

ScreenScene project(const Scene& scene, const View& view) {
  ScreenScene s;
  s.faces = scene.faces.size();
  const auto& m = view.m;
  std::vector<Vec3> p;
  std::vector<H4> hv;
  for (std::size_t f = 0; f < scene.faces.size(); ++f) {
    p.clear();
    for (std::uint32_t v : scene.faces[f]) {
      const Vec3& q = scene.vertices[v];
      if (!p.empty() && q.x == p.back().x && q.y == p.back().y && q.z == p.back().z) continue;
      p.push_back(q);
    }
    while (p.size() > 1 && p.front().x == p.back().x && p.front().y == p.back().y && p.front().z == p.back().z)
      p.pop_back();
    if (p.size() < 3) continue;
    const Vec3 n = newell_normal(p);
    if (n.x == 0 && n.y == 0 && n.z == 0) continue;   // collinear (in doubles)
    const std::size_t before = s.pieces.size();
    for (const auto& wp : world_pieces(p, n)) {
      hv.clear();
      for (int k : wp) {
        const Vec3& q = p[k];
        hv.push_back({m[0][0] * q.x + m[0][1] * q.y + m[0][2] * q.z + m[0][3],
                      m[1][0] * q.x + m[1][1] * q.y + m[1][2] * q.z + m[1][3],
                      m[2][0] * q.x + m[2][1] * q.y + m[2][2] * q.z + m[2][3],
                      m[3][0] * q.x + m[3][1] * q.y + m[3][2] * q.z + m[3][3]});
      }
      if (view.perspective) hv = clip_near(hv);
      emit(s, static_cast<int>(f), hv, view.perspective);
    }
    if (s.pieces.size() > before) ++s.faces_drawn;
  }
  return s;
}

Window window_for_box(double xmin, double xmax, double ymin, double ymax, int R) {
  Window w;
  w.R = R;
  double side = std::max(xmax - xmin, ymax - ymin);
  if (!(side > 0) || !std::isfinite(side)) {
    side = 1;
    if (!std::isfinite(xmin + xmax + ymin + ymax)) xmin = xmax = ymin = ymax = 0;
  }
  w.pixel = side / R;
  w.x0 = (xmin + xmax) / 2 - side / 2;
  w.y0 = (ymin + ymax) / 2 - side / 2;
  return w;
}

Window window_for(const ScreenScene& s, int R) { return window_for_box(s.xmin, s.xmax, s.ymin, s.ymax, R); }

const char* name(Method m) {
  switch (m) {
    case Method::ZBuffer: return "z-buffer";
    case Method::ScanLine: return "scan-line";
    case Method::Warnock: return "warnock";
    case Method::RayCast: return "ray-cast";
  }
  return "?";
}

Image render(Method m, const ScreenScene& s, const Window& w) {
  switch (m) {
    case Method::ZBuffer: return zbuffer(s, w);
    case Method::ScanLine: return scanline(s, w);
    case Method::Warnock: return warnock(s, w);
    case Method::RayCast: return raycast(s, w);
  }
  return {};
}

namespace {

std::uint64_t pair_key(std::uint32_t f, std::uint32_t g) {
  return static_cast<std::uint64_t>(std::min(f, g)) << 32 | std::max(f, g);
}

std::int32_t find(std::vector<std::int32_t>& parent, std::int32_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace

bool LineRule::drawn(std::int32_t f, std::int32_t g, double x, double y, double pixel) const {
  if (f == g) return false;
  if (f < 0 || g < 0 || patch.empty()) return true;
  if (patch[f] != patch[g]) return true;
  if (std::binary_search(creases.begin(), creases.end(),
                         pair_key(static_cast<std::uint32_t>(f), static_cast<std::uint32_t>(g))))
    return true;
  const double df = a[f] * x + (b[f] * y + c[f]), dg = a[g] * x + (b[g] * y + c[g]);
  return std::abs(df - dg) > 2 * pixel * (grad[f] + grad[g]);
}

LineRule all_changes() { return {}; }

LineRule line_rule(const Scene& scene, const View& view, const ScreenScene& s, double crease_deg) {
  const std::size_t nf = scene.faces.size();
  // The faces around every vertex (by index), as compressed lists.
  std::vector<std::uint32_t> start(scene.vertices.size() + 1, 0);
  for (const auto& fv : scene.faces)
    for (std::uint32_t v : fv) ++start[v + 1];
  for (std::size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  std::vector<std::uint32_t> around(start.back());
  {
    std::vector<std::uint32_t> at(start.begin(), start.end() - 1);
    for (std::size_t f = 0; f < nf; ++f)
      for (std::uint32_t v : scene.faces[f]) around[at[v]++] = static_cast<std::uint32_t>(f);
  }
  // Normal and facing (+1 front: the normal points towards the eye) per face.
  std::vector<Vec3> normal(nf);
  std::vector<int> facing(nf, 0);
  for (std::size_t f = 0; f < nf; ++f) {
    std::vector<Vec3> p;
    for (auto v : scene.faces[f]) p.push_back(scene.vertices[v]);
    if (p.empty()) continue;
    normal[f] = newell_normal(p);
    const Vec3 d = view.perspective ? sub(p[0], view.eye) : Vec3{view.m[2][0], view.m[2][1], view.m[2][2]};
    const double sd = dot(normal[f], d);
    facing[f] = sd < 0 ? 1 : sd > 0 ? -1 : 0;
  }
  const double cosine = std::cos(crease_deg * M_PI / 180);
  LineRule out;
  out.patch.resize(nf);
  for (std::size_t f = 0; f < nf; ++f) out.patch[f] = static_cast<std::int32_t>(f);
  for (std::size_t v = 0; v + 1 < start.size(); ++v)
    for (std::uint32_t i = start[v]; i < start[v + 1]; ++i)
      for (std::uint32_t k = i + 1; k < start[v + 1]; ++k) {
        const std::uint32_t f = around[i], g = around[k];
        if (f == g) continue;
        const Vec3 &nf_ = normal[f], &ng = normal[g];
        const bool smooth = facing[f] != 0 && facing[f] == facing[g] &&
                            dot(nf_, ng) >= cosine * std::sqrt(dot(nf_, nf_)) * std::sqrt(dot(ng, ng));
        if (smooth) {
          const std::int32_t rf = find(out.patch, static_cast<std::int32_t>(f)),
                             rg = find(out.patch, static_cast<std::int32_t>(g));
          if (rf != rg) out.patch[std::max(rf, rg)] = std::min(rf, rg);
        } else {
          out.creases.push_back(pair_key(f, g));
        }
      }
  for (std::size_t f = 0; f < nf; ++f) out.patch[f] = find(out.patch, static_cast<std::int32_t>(f));
  std::sort(out.creases.begin(), out.creases.end());
  out.creases.erase(std::unique(out.creases.begin(), out.creases.end()), out.creases.end());
  // Depth planes: each face's first piece.
  out.a.assign(nf, 0);
  out.b.assign(nf, 0);
  out.c.assign(nf, 0);
  out.grad.assign(nf, 0);
  std::vector<char> seen(nf, 0);
  for (const Piece& p : s.pieces) {
    if (p.face < 0 || static_cast<std::size_t>(p.face) >= nf || seen[p.face]) continue;
    seen[p.face] = 1;
    out.a[p.face] = p.a;
    out.b[p.face] = p.b;
    out.c[p.face] = p.c;
    out.grad[p.face] = std::sqrt(p.a * p.a + p.b * p.b);
  }
  return out;
}

}  // namespace vismap::raster
