#include "bench/scene_gen.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace vismap::gen {
namespace {

std::uint64_t splitmix64(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

// Shortest round-trip text of a double, for names and OFF output.
std::string fmt(double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

Vec3 add(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 sub(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 mul(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// A uniformly random unit vector: rejection sampling in the unit ball, then
// normalising (sqrt only, so it is reproducible everywhere).
Vec3 random_unit(Rng& rng) {
  for (;;) {
    Vec3 v{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    double r2 = dot(v, v);
    if (r2 > 1e-6 && r2 <= 1) return mul(v, 1 / std::sqrt(r2));
  }
}

std::uint32_t vertex_index(const Scene& s) {
  if (s.vertices.size() >= std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("scene_gen: more than 2^32 - 1 vertices");
  return static_cast<std::uint32_t>(s.vertices.size());
}

}  // namespace

// Appends a closed box [lo, hi] as 8 shared vertices and 6 outward quads.
// Vertex k of the box has hi's coordinate on axis a exactly when bit a of k is set.
void add_box(Scene& s, Vec3 lo, Vec3 hi) {
  const std::uint32_t b = vertex_index(s);
  for (int k = 0; k < 8; ++k)
    s.vertices.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
  // Each quad counter-clockwise seen from outside (normal = -x, +x, -y, +y, -z, +z).
  static constexpr std::uint32_t quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                                {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) s.faces.push_back({b + q[0], b + q[1], b + q[2], b + q[3]});
}

Rng::Rng(std::uint64_t seed) {
  for (auto& w : s_) w = splitmix64(seed);
}

std::uint64_t Rng::next() {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double Rng::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

double Rng::uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

Scene random_squares(std::size_t n, double side, std::uint64_t seed) {
  if (!(side > 0 && side <= 1)) throw std::invalid_argument("random_squares: need 0 < side <= 1");
  Scene s;
  s.file = "random_squares(n=" + std::to_string(n) + ",side=" + fmt(side) +
           ",seed=" + std::to_string(seed) + ")";
  s.vertices.reserve(4 * n);
  s.faces.reserve(n);
  Rng rng(seed);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = rng.uniform(0, 1 - side), y = rng.uniform(0, 1 - side);
    const double z = rng.uniform();  // 53 random bits: equal depths are practically impossible
    const std::uint32_t b = vertex_index(s);
    s.vertices.push_back({x, y, z});
    s.vertices.push_back({x + side, y, z});
    s.vertices.push_back({x + side, y + side, z});
    s.vertices.push_back({x, y + side, z});
    s.faces.push_back({b, b + 1, b + 2, b + 3});
  }
  return s;
}

Scene random_squares_depth(std::size_t n, double depth_complexity, std::uint64_t seed) {
  if (n == 0 || !(depth_complexity > 0) || depth_complexity > static_cast<double>(n))
    throw std::invalid_argument("random_squares_depth: need 0 < D <= n");
  Scene s = random_squares(n, std::sqrt(depth_complexity / static_cast<double>(n)), seed);
  s.file = "random_squares(n=" + std::to_string(n) + ",D=" + fmt(depth_complexity) +
           ",seed=" + std::to_string(seed) + ")";
  return s;
}

Scene corner_fans(std::size_t n, int hubs, std::uint64_t seed) {
  if (hubs < 1) throw std::invalid_argument("corner_fans: need hubs >= 1");
  Scene s;
  s.file = "corner_fans(n=" + std::to_string(n) + ",hubs=" + std::to_string(hubs) + ",seed=" + std::to_string(seed) + ")";
  Rng rng(seed);
  for (int h = 0; h < hubs; ++h) s.vertices.push_back({rng.uniform(0.3, 0.7), rng.uniform(0.3, 0.7), rng.uniform(0.3, 0.7)});
  for (std::size_t i = 0; i < n; ++i) {
    const auto hub = static_cast<std::uint32_t>(rng.next() % static_cast<std::uint64_t>(hubs));
    const Vec3 c = s.vertices[hub];
    const auto b = static_cast<std::uint32_t>(s.vertices.size());
    for (int k = 0; k < 2; ++k)
      s.vertices.push_back({c.x + rng.uniform(-0.4, 0.4), c.y + rng.uniform(-0.4, 0.4), c.z + rng.uniform(-0.4, 0.4)});
    s.faces.push_back({hub, b, b + 1});
  }
  return s;
}

Scene holed_plates(std::size_t n, std::uint64_t seed) {
  Scene s;
  s.file = "holed_plates(n=" + std::to_string(n) + ",seed=" + std::to_string(seed) + ")";
  Rng rng(seed);
  auto grid = [&](int lo, int hi) { return (lo + static_cast<int>(rng.next() % static_cast<std::uint64_t>(hi - lo + 1))) / 64.0; };
  static const Vec3 kDirs[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, -1}, {1, 0, 1}, {1, -1, 1}, {-1, 0, 2}};
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 a = kDirs[rng.next() % 8];
    Vec3 b = kDirs[rng.next() % 8];
    while (b.x * a.y - b.y * a.x == 0 && b.y * a.z - b.z * a.y == 0 && b.z * a.x - b.x * a.z == 0) b = kDirs[rng.next() % 8];
    const Vec3 o{grid(0, 40), grid(0, 40), grid(0, 40)};
    const double w = grid(24, 40), h = grid(24, 40);   // the plate is [0, w] x [0, h] in (a, b)
    auto at = [&](double u, double v) {
      s.vertices.push_back({o.x + u * a.x + v * b.x, o.y + u * a.y + v * b.y, o.z + u * a.z + v * b.z});
      return static_cast<std::uint32_t>(s.vertices.size() - 1);
    };
    const std::uint32_t c0 = at(0, 0), c1 = at(w, 0), c2 = at(w, h), c3 = at(0, h);
    s.faces.push_back({c0, c1, c2, c3});
    std::vector<IndexRing> holes;
    // (Quarters and 1/64ths of multiples of 1/64: few bits, so every corner's
    // coordinates are exact sums and the plate exactly planar.)
    for (int cu = 0; cu < 4; ++cu)
      for (int cv = 0; cv < 4; ++cv) {
        if (rng.next() % 2 == 0) continue;
        // Inside the cell, 1/64 away from its sides (the cells are 6/64 or more).
        const double u0 = w * cu / 4 + 1 / 64.0, u1 = w * (cu + 1) / 4 - 1 / 64.0;
        const double v0 = h * cv / 4 + 1 / 64.0, v1 = h * (cv + 1) / 4 - 1 / 64.0;
        IndexRing r{at(u0, v0), at(u1, v0), at(u1, v1)};
        if (rng.next() % 2) r.push_back(at(u0 + (u1 - u0) / 4, v1));
        if (rng.next() % 2) std::reverse(r.begin(), r.end());
        holes.push_back(std::move(r));
      }
    // Sometimes a hole at the rectangle's far corner, sharing it (the cell there is left empty).
    if (rng.next() % 2 && !holes.empty() && holes.back().size() == 3) {
      holes.pop_back();
      holes.push_back({c2, at(w * 0.75, h * 0.875), at(w * 0.875, h * 0.75)});
    }
    s.holes.resize(s.faces.size());
    s.holes.back() = std::move(holes);
  }
  return s;
}

Scene random_triangles(std::size_t n, double size, std::uint64_t seed) {
  if (!(size > 0 && size <= 1)) throw std::invalid_argument("random_triangles: need 0 < size <= 1");
  Scene s;
  s.file = "random_triangles(n=" + std::to_string(n) + ",size=" + fmt(size) +
           ",seed=" + std::to_string(seed) + ")";
  s.vertices.reserve(3 * n);
  s.faces.reserve(n);
  Rng rng(seed);
  const double r = size / 2;                   // circumradius
  const double h = std::sqrt(3.0) / 2;         // sin 120 degrees
  for (std::size_t i = 0; i < n; ++i) {
    // Centre at least r from every side of the cube, so all vertices are inside.
    const Vec3 c{rng.uniform(r, 1 - r), rng.uniform(r, 1 - r), rng.uniform(r, 1 - r)};
    const Vec3 normal = random_unit(rng);
    // A random direction in the triangle's plane; (a, b, normal) is right-handed,
    // so the vertices run counter-clockwise about the (random) normal.
    Vec3 a;
    for (;;) {
      const Vec3 v = random_unit(rng);
      a = sub(v, mul(normal, dot(v, normal)));
      const double len2 = dot(a, a);
      if (len2 > 1e-6) {
        a = mul(a, 1 / std::sqrt(len2));
        break;
      }
    }
    const Vec3 b = cross(normal, a);
    const std::uint32_t base = vertex_index(s);
    s.vertices.push_back(add(c, mul(a, r)));
    s.vertices.push_back(add(c, add(mul(a, -r / 2), mul(b, r * h))));
    s.vertices.push_back(add(c, add(mul(a, -r / 2), mul(b, -r * h))));
    s.faces.push_back({base, base + 1, base + 2});
  }
  return s;
}

Scene cube_array(int k, double gap) {
  if (k < 0 || !(gap > 0)) throw std::invalid_argument("cube_array: need k >= 0 and gap > 0");
  Scene s;
  s.file = "cube_array(k=" + std::to_string(k) + ",gap=" + fmt(gap) + ")";
  const double pitch = 1 + gap;
  const auto count = static_cast<std::size_t>(k) * static_cast<std::size_t>(k) * static_cast<std::size_t>(k);
  s.vertices.reserve(8 * count);
  s.faces.reserve(6 * count);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      for (int l = 0; l < k; ++l) {
        const Vec3 lo{i * pitch, j * pitch, l * pitch};
        add_box(s, lo, {lo.x + 1, lo.y + 1, lo.z + 1});
      }
  return s;
}

Scene sphere(int nu, int nv, double radius, Vec3 center) {
  if (nu < 3 || nv < 2 || !(radius > 0))
    throw std::invalid_argument("sphere: need nu >= 3, nv >= 2, radius > 0");
  Scene s;
  s.file = "sphere(nu=" + std::to_string(nu) + ",nv=" + std::to_string(nv) +
           ",radius=" + fmt(radius) + ")";
  const double pi = 3.14159265358979323846;
  const auto nu32 = static_cast<std::uint32_t>(nu);
  // Vertex 0: north pole; then rings 1..nv-1 of nu vertices each; last: south pole.
  s.vertices.push_back(add(center, {0, 0, radius}));
  for (int i = 1; i < nv; ++i) {
    const double theta = pi * i / nv;
    for (int j = 0; j < nu; ++j) {
      const double phi = 2 * pi * j / nu;
      s.vertices.push_back(add(center, {radius * std::sin(theta) * std::cos(phi),
                                        radius * std::sin(theta) * std::sin(phi),
                                        radius * std::cos(theta)}));
    }
  }
  const auto south = static_cast<std::uint32_t>(s.vertices.size());
  s.vertices.push_back(add(center, {0, 0, -radius}));
  auto ring = [nu32](std::uint32_t i, std::uint32_t j) { return 1 + (i - 1) * nu32 + j % nu32; };
  // Counter-clockwise seen from outside: phi grows eastwards, theta southwards.
  for (std::uint32_t j = 0; j < nu32; ++j) s.faces.push_back({0, ring(1, j), ring(1, j + 1)});
  for (std::uint32_t i = 1; i + 1 < static_cast<std::uint32_t>(nv); ++i)
    for (std::uint32_t j = 0; j < nu32; ++j)
      s.faces.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)});
  const auto last = static_cast<std::uint32_t>(nv - 1);
  for (std::uint32_t j = 0; j < nu32; ++j)
    s.faces.push_back({south, ring(last, j + 1), ring(last, j)});
  return s;
}

Scene interpenetrating_boxes(std::size_t n, std::uint64_t seed) {
  Scene s;
  s.file = "interpenetrating_boxes(n=" + std::to_string(n) + ",seed=" + std::to_string(seed) + ")";
  Rng rng(seed);
  for (std::size_t i = 0; i < n; ++i) {
    // Centres within 0.05 of the middle and thin half-widths >= 0.08 make every
    // pair overlap on all three axes; a different long axis makes them cross.
    double c[3], h[3];
    for (int a = 0; a < 3; ++a) {
      c[a] = rng.uniform(0.45, 0.55);
      h[a] = rng.uniform(0.08, 0.2);
    }
    h[i % 3] = rng.uniform(0.35, 0.45);
    add_box(s, {c[0] - h[0], c[1] - h[1], c[2] - h[2]}, {c[0] + h[0], c[1] + h[1], c[2] + h[2]});
  }
  return s;
}

Scene terrain(int k, std::uint64_t seed) {
  if (k < 1) throw std::invalid_argument("terrain: need k >= 1");
  Scene s;
  s.file = "terrain(k=" + std::to_string(k) + ",seed=" + std::to_string(seed) + ")";
  Rng rng(seed);
  // Value noise: octave o has a (g+1)^2 lattice of random values, g = 2^(o+1)
  // cells across, amplitude halving per octave; smoothstep-blended inside a cell.
  constexpr std::size_t octaves = 4;
  std::vector<std::vector<double>> lattice(octaves);
  for (std::size_t o = 0; o < octaves; ++o) {
    const std::size_t g = std::size_t{2} << o;
    lattice[o].resize((g + 1) * (g + 1));
    for (double& v : lattice[o]) v = rng.uniform(-1, 1);
  }
  auto height = [&](double x, double y) {
    double z = 0, amp = 0.1;
    for (std::size_t o = 0; o < octaves; ++o, amp /= 2) {
      const std::size_t g = std::size_t{2} << o;
      const double fx = x * static_cast<double>(g), fy = y * static_cast<double>(g);
      const std::size_t ix = std::min(static_cast<std::size_t>(fx), g - 1);
      const std::size_t iy = std::min(static_cast<std::size_t>(fy), g - 1);
      double tx = fx - static_cast<double>(ix), ty = fy - static_cast<double>(iy);
      tx = tx * tx * (3 - 2 * tx);
      ty = ty * ty * (3 - 2 * ty);
      const auto at = [&](std::size_t i, std::size_t j) { return lattice[o][j * (g + 1) + i]; };
      const double bottom = at(ix, iy) + (at(ix + 1, iy) - at(ix, iy)) * tx;
      const double top = at(ix, iy + 1) + (at(ix + 1, iy + 1) - at(ix, iy + 1)) * tx;
      z += amp * (bottom + (top - bottom) * ty);
    }
    return z;
  };
  const auto k1 = static_cast<std::uint32_t>(k) + 1;
  s.vertices.reserve(static_cast<std::size_t>(k1) * k1);
  for (std::uint32_t j = 0; j < k1; ++j)
    for (std::uint32_t i = 0; i < k1; ++i) {
      const double x = static_cast<double>(i) / k, y = static_cast<double>(j) / k;
      s.vertices.push_back({x, y, height(x, y)});
    }
  s.faces.reserve(2 * static_cast<std::size_t>(k) * static_cast<std::size_t>(k));
  for (std::uint32_t j = 0; j + 1 < k1; ++j)
    for (std::uint32_t i = 0; i + 1 < k1; ++i) {
      const std::uint32_t a = j * k1 + i, b = a + 1, c = a + k1 + 1, d = a + k1;
      s.faces.push_back({a, b, c});  // counter-clockwise seen from +z
      s.faces.push_back({a, c, d});
    }
  return s;
}

void append_scene(Scene& dst, const Scene& src) {
  const std::uint32_t offset = vertex_index(dst);
  if (src.vertices.size() > std::numeric_limits<std::uint32_t>::max() - offset)
    throw std::length_error("append_scene: more than 2^32 - 1 vertices");
  dst.vertices.insert(dst.vertices.end(), src.vertices.begin(), src.vertices.end());
  dst.faces.reserve(dst.faces.size() + src.faces.size());
  for (const auto& f : src.faces) {
    auto& g = dst.faces.emplace_back(f);
    for (auto& v : g) v += offset;
  }
  dst.file = dst.file.empty() ? src.file : src.file.empty() ? dst.file : dst.file + "+" + src.file;
}

void transform(Scene& scene, double scale, Vec3 offset) {
  for (auto& p : scene.vertices) p = add(mul(p, scale), offset);
}

std::string to_off(const Scene& scene) {
  std::string out = "OFF\n" + std::to_string(scene.vertices.size()) + " " +
                    std::to_string(scene.faces.size()) + " 0\n";
  for (const auto& p : scene.vertices) out += fmt(p.x) + " " + fmt(p.y) + " " + fmt(p.z) + "\n";
  for (const auto& f : scene.faces) {
    out += std::to_string(f.size());
    for (auto v : f) out += " " + std::to_string(v);
    out += "\n";
  }
  return out;
}

}  // namespace vismap::gen
