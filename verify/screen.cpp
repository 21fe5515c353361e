// Projection, near-plane clipping and face pieces (spec "Faces", "Camera").
#include "verify/screen.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "verify/rational.h"

namespace vismap_check {
namespace {

using V3 = std::array<mpq_class, 3>;
using V4 = std::array<mpq_class, 4>;

V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross3(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
mpq_class dot3(const V3& a, const V3& b) {
  mpq_class d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  return d;
}
bool is_zero(const V3& a) { return a[0] == 0 && a[1] == 0 && a[2] == 0; }

// Newell's vector: twice the vector area; exact normal of a planar polygon.
V3 newell(const std::vector<V3>& p) {
  V3 n{0, 0, 0};
  for (std::size_t i = 0, k = p.size(); i < k; ++i) {
    const V3& a = p[i];
    const V3& b = p[(i + 1) % k];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  return n;
}

// A polygon in homogeneous screen coordinates with a role for each edge.
struct HPoly {
  std::vector<V4> v;
  std::vector<Role> role;
};

template <class T>
void drop_repeats(std::vector<T>& v, std::vector<Role>& role) {
  // Removing v[i] when v[i] == v[i+1] keeps the roles of the two real edges.
  bool changed = true;
  while (changed && v.size() > 1) {
    changed = false;
    for (std::size_t i = 0; i < v.size() && v.size() > 1; ++i) {
      std::size_t j = (i + 1) % v.size();
      if (v[i] == v[j]) {
        v.erase(v.begin() + static_cast<std::ptrdiff_t>(i));
        role.erase(role.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        break;
      }
    }
  }
}

// Sutherland-Hodgman against coordinate c >= 0, on the 4-vectors (before any
// division), so the cut is exact and the near plane's points stay in the closure.
HPoly clip(const HPoly& in, int c) {
  HPoly out;
  auto emit = [&](const V4& p, Role r) {
    out.v.push_back(p);
    out.role.push_back(r);
  };
  auto cut = [&](const V4& a, const V4& b) {
    mpq_class t = a[c] / (a[c] - b[c]);
    V4 p;
    for (int k = 0; k < 4; ++k) p[k] = a[k] + t * (b[k] - a[k]);
    return p;
  };
  for (std::size_t i = 0, n = in.v.size(); i < n; ++i) {
    const V4& a = in.v[i];
    const V4& b = in.v[(i + 1) % n];
    int sa = sgn(a[c]), sb = sgn(b[c]);
    Role r = in.role[i];
    if (sa >= 0) {
      if (sb >= 0) {
        emit(a, r);
      } else if (sa > 0) {
        emit(a, r);
        emit(cut(a, b), Role::Clip);
      } else {
        emit(a, Role::Clip);   // a on the plane, the edge leaves: next kept edge is a cut
      }
    } else if (sb > 0) {
      emit(cut(a, b), r);
    }
  }
  drop_repeats(out.v, out.role);
  return out;
}

struct V3Eq {
  mpq_class x, y, d;
  bool operator==(const V3Eq& o) const { return x == o.x && y == o.y && d == o.d; }
};

struct WorldRing {
  std::vector<V3> p;
  std::vector<Role> role;
};

class Projector {
 public:
  Projector(const MapDoc& doc, Screen& out, Failures& fail) : doc_(doc), out_(out), fail_(fail) {}

  // world polygon (no consecutive repeats) with roles -> one Piece (or none)
  void add(std::uint32_t face, const std::vector<V3>& world, const std::vector<Role>& roles, const V3& normal) {
    add(face, {WorldRing{world, roles}}, normal);
  }

  // A planar polygon with holes (rings[0] the outer ring, each hole turned
  // against it), each ring projected and clipped on its own -> one Piece.
  void add(std::uint32_t face, const std::vector<WorldRing>& rings, const V3& normal) {
    Piece pc;
    pc.face = face;
    pc.normal = normal;
    std::vector<V3> outer;   // ring 0 on the screen, (x, y, depth)
    for (const WorldRing& r : rings) {
      std::vector<V3Eq> s;
      std::vector<Role> role;
      if (!project(face, r, s, role)) return;
      if (s.size() < 3) {
        if (&r == &rings[0]) return;   // the outer ring is gone: so is the piece
        continue;
      }
      const std::size_t first = pc.xy.size();
      for (std::size_t i = 0; i < s.size(); ++i) {
        pc.xy.push_back(P2{s[i].x, s[i].y});
        pc.depth.push_back(s[i].d);
        pc.role.push_back(role[i]);
        if (&r == &rings[0]) outer.push_back(V3{s[i].x, s[i].y, s[i].d});
        if (rings.size() > 1) pc.ring_next.push_back(static_cast<std::uint32_t>(i + 1 == s.size() ? first : first + i + 1));
      }
    }
    V3 n = newell(outer);   // (x, y, depth) space: projective images of planes are planes
    pc.orient = sgn(n[2]);
    if (pc.orient != 0) {
      pc.pa = -n[0] / n[2];
      pc.pb = -n[1] / n[2];
      pc.pc = outer[0][2] - pc.pa * outer[0][0] - pc.pb * outer[0][1];
      for (std::size_t i = 0; i < pc.xy.size(); ++i)
        if (pc.pa * pc.xy[i].x + pc.pb * pc.xy[i].y + pc.pc != pc.depth[i])
          fail_.add("internal: face " + std::to_string(face) + " is not planar on the screen");
      mpz_lcm(pc.il.get_mpz_t(), pc.pa.get_den_mpz_t(), pc.pb.get_den_mpz_t());
      mpz_lcm(pc.il.get_mpz_t(), pc.il.get_mpz_t(), pc.pc.get_den_mpz_t());
      pc.ia = pc.pa.get_num() * (pc.il / pc.pa.get_den());
      pc.ib = pc.pb.get_num() * (pc.il / pc.pb.get_den());
      pc.ic = pc.pc.get_num() * (pc.il / pc.pc.get_den());
    }
    pc.box = box_of(pc.xy);
    // Convex: every vertex on the inner side (or the line) of every edge.
    pc.convex = pc.orient != 0 && pc.ring_next.empty();
    for (std::size_t i = 0, k = pc.xy.size(); i < k && pc.convex; ++i)
      for (const P2& v : pc.xy)
        if (orient(pc.xy[i], pc.xy[(i + 1) % k], v) == -pc.orient) {
          pc.convex = false;
          break;
        }
    out_.pieces.push_back(std::move(pc));
  }

 private:
  // One ring through the view matrix, clipped at the near plane in perspective:
  // its screen points and roles (fewer than three: nothing left). False, with
  // a failure, when a kept point has W <= 0.
  bool project(std::uint32_t face, const WorldRing& r, std::vector<V3Eq>& s, std::vector<Role>& role) {
    HPoly h;
    for (const V3& p : r.p) {
      V4 q;
      for (int i = 0; i < 4; ++i) q[i] = doc_.m[i][0] * p[0] + doc_.m[i][1] * p[1] + doc_.m[i][2] * p[2] + doc_.m[i][3];
      h.v.push_back(std::move(q));
    }
    h.role = r.role;
    if (doc_.perspective) {
      h = clip(h, 3);   // W >= 0
      h = clip(h, 2);   // Z >= 0: the near plane is depth 0
      if (h.v.size() < 3) return true;
      bool all_on_near = true;
      for (const V4& p : h.v) all_on_near = all_on_near && p[2] == 0;
      if (all_on_near) return true;   // "at or behind the near plane" is clipped away
    }
    for (const V4& p : h.v) {
      if (sgn(p[3]) <= 0) {
        fail_.add("projection: face " + std::to_string(face) + " has a kept point with W = " + str(p[3]) +
                  " <= 0 under the map's view_matrix");
        return false;
      }
      s.push_back({p[0] / p[3], p[1] / p[3], p[2] / p[3]});
    }
    role = std::move(h.role);
    drop_repeats(s, role);
    if (s.size() < 3) s.clear();
    return true;
  }

  const MapDoc& doc_;
  Screen& out_;
  Failures& fail_;
};

// Simple: no two edges of the closed ring meet, except neighbours at their
// shared corner, and there only (folding back along the same line overlaps).
bool is_simple(const std::vector<P2>& r) {
  const std::size_t n = r.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool neighbours = j == i + 1 || (i == 0 && j == n - 1);
      const Meet m = meet(r[i], r[(i + 1) % n], r[j], r[(j + 1) % n]);
      if (neighbours ? m == Meet::Overlap : m != Meet::None) return false;
    }
  return true;
}

// A planar polygon in a coordinate plane its normal n is not parallel to (drop
// a coordinate where n is not zero): a one-to-one image, so simple iff simple.
std::vector<P2> flatten(const std::vector<V3>& w, const V3& n) {
  const int drop = n[2] != 0 ? 2 : n[1] != 0 ? 1 : 0;
  std::vector<P2> r;
  for (const V3& p : w) r.push_back(drop == 2 ? P2{p[0], p[1]} : drop == 1 ? P2{p[2], p[0]} : P2{p[1], p[2]});
  return r;
}

// A ring's corners as exact points, consecutive repeats dropped; false when
// an index is out of range or a vertex is not finite.
bool world_ring(const vismap::Scene& scene, const vismap::IndexRing& idx, std::vector<V3>& w) {
  for (std::uint32_t i : idx) {
    if (i >= scene.vertices.size()) return false;
    const vismap::Vec3& v = scene.vertices[i];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return false;
    V3 p{mpq_class(v.x), mpq_class(v.y), mpq_class(v.z)};   // doubles are exact rationals
    if (w.empty() || w.back() != p) w.push_back(std::move(p));
  }
  while (w.size() > 1 && w.front() == w.back()) w.pop_back();
  return true;
}

// A face with holes (Scene: planar, holes inside the outer ring): one piece of
// several rings, every edge a boundary edge. An outer ring with no area drops
// the face, as for any polygon; the rest of what Scene requires is the
// engines' to refuse, and only planarity and the holes' areas are checked here.
void add_holed_face(const vismap::Scene& scene, std::uint32_t f, Projector& proj, Failures& fail) {
  std::vector<WorldRing> rings(1);
  const std::string face = "scene: face " + std::to_string(f);
  if (!world_ring(scene, scene.faces[f], rings[0].p))
    return fail.add(face + " has a vertex index out of range or a vertex not finite");
  const V3 n = newell(rings[0].p);   // the outer ring's normal: its turn says which side is the front
  if (rings[0].p.size() < 3 || is_zero(n)) return;
  for (const vismap::IndexRing& idx : scene.holes_of(f)) {
    WorldRing h;
    if (!world_ring(scene, idx, h.p)) return fail.add(face + " has a vertex index out of range or a vertex not finite");
    rings.push_back(std::move(h));
  }
  for (WorldRing& r : rings) {
    for (const V3& p : r.p)
      if (dot3(n, sub(p, rings[0].p[0])) != 0) return fail.add(face + " has holes but is not planar");
    const mpq_class turn = dot3(newell(r.p), n);
    if (turn == 0) return fail.add(face + " has a hole with no area");
    if (&r != &rings[0] && turn > 0) std::reverse(r.p.begin(), r.p.end());   // turned against the outer ring
    r.role.assign(r.p.size(), Role::Boundary);
  }
  proj.add(f, rings, n);
}

}  // namespace

int Piece::depth_cmp(const P2& q, const mpq_class& d) const {
  thread_local mpz_class common, x, t;
  const mpz_class& xn = q.x.get_num();
  const mpz_class& xd = q.x.get_den();
  const mpz_class& yn = q.y.get_num();
  const mpz_class& yd = q.y.get_den();
  // il (depth - d) xd yd dd = (ia xn yd + ib yn xd + ic xd yd) dd - il dn xd yd
  mpz_mul(common.get_mpz_t(), xd.get_mpz_t(), yd.get_mpz_t());
  mpz_mul(x.get_mpz_t(), ia.get_mpz_t(), xn.get_mpz_t());
  mpz_mul(x.get_mpz_t(), x.get_mpz_t(), yd.get_mpz_t());
  mpz_mul(t.get_mpz_t(), ib.get_mpz_t(), yn.get_mpz_t());
  mpz_addmul(x.get_mpz_t(), t.get_mpz_t(), xd.get_mpz_t());
  mpz_addmul(x.get_mpz_t(), ic.get_mpz_t(), common.get_mpz_t());
  mpz_mul(x.get_mpz_t(), x.get_mpz_t(), d.get_den_mpz_t());
  mpz_mul(t.get_mpz_t(), il.get_mpz_t(), d.get_num_mpz_t());
  mpz_mul(t.get_mpz_t(), t.get_mpz_t(), common.get_mpz_t());
  int c = cmp(x, t);
  return c > 0 ? 1 : c < 0 ? -1 : 0;
}

Where locate(const P2& q, const Piece& p) {
  return locate_edges(q, p.xy, [&p](std::size_t i) { return p.next(i); });
}

bool is_crease(const std::array<mpq_class, 3>& n1, const std::array<mpq_class, 3>& n2, const mpq_class& c) {
  mpq_class d = dot3(n1, n2);
  mpq_class p = dot3(n1, n1) * dot3(n2, n2);   // (|n1| |n2|)^2
  mpq_class lhs = d * d, rhs = c * c * p;
  int sc = sgn(c);
  if (sc > 0) return d < 0 || lhs < rhs;       // right side >= 0
  if (sc == 0) return d < 0;
  return d < 0 && lhs > rhs;                   // right side < 0: need d < 0 and |d| > |c||n1||n2|
}

Kind edge_kind(const std::vector<const Piece*>& owners, const mpq_class& cos_crease) {
  if (owners.size() == 1) return Kind::Border;
  if (owners.size() >= 3) return Kind::Crease;
  int o1 = owners[0]->orient, o2 = owners[1]->orient;
  if ((o1 > 0) != (o2 > 0)) return Kind::Silhouette;
  if (o1 == o2 && o1 != 0)
    return is_crease(owners[0]->normal, owners[1]->normal, cos_crease) ? Kind::Crease : Kind::Smooth;
  return Kind::Smooth;
}

Screen make_screen(const vismap::Scene& scene, const MapDoc& doc, double crease_deg, bool smooth, Failures& fail) {
  Screen out;
  out.faces = scene.faces.size();
  // The spec's c: the double cos(theta * pi / 180), then taken exactly.
  double c = std::cos(crease_deg * std::numbers::pi / 180.0);
  if (!std::isfinite(c)) {
    fail.add("options: the crease angle " + std::to_string(crease_deg) + " is not finite");
    c = 1;
  }
  out.cos_crease = mpq_class(c);
  out.smooth = smooth;
  Projector proj(doc, out, fail);
  for (std::size_t f = 0; f < scene.faces.size(); ++f) {
    if (!scene.holes_of(f).empty()) {
      add_holed_face(scene, static_cast<std::uint32_t>(f), proj, fail);
      continue;
    }
    const auto& idx = scene.faces[f];
    std::vector<V3> w;
    bool bad = false;
    for (std::uint32_t i : idx) {
      if (i >= scene.vertices.size()) {
        bad = true;
        break;
      }
      const vismap::Vec3& v = scene.vertices[i];
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
        bad = true;
        break;
      }
      V3 p{mpq_class(v.x), mpq_class(v.y), mpq_class(v.z)};   // doubles are exact rationals
      if (w.empty() || w.back() != p) w.push_back(std::move(p));
    }
    if (bad) {
      fail.add("scene: face " + std::to_string(f) + " has a vertex index out of range or a vertex not finite");
      continue;
    }
    while (w.size() > 1 && w.front() == w.back()) w.pop_back();
    // Degenerate: fewer than three distinct vertices, or all collinear.
    if (w.size() < 3) continue;
    std::size_t j = 1, k = 0;
    V3 n{0, 0, 0};
    for (std::size_t i = 2; i < w.size() && k == 0; ++i) {
      V3 t = cross3(sub(w[j], w[0]), sub(w[i], w[0]));
      if (!is_zero(t)) {
        k = i;
        n = t;
      }
    }
    if (k == 0) continue;   // w[1] != w[0] after dropping repeats, so this means collinear
    bool planar = true;
    for (const V3& p : w) planar = planar && dot3(n, sub(p, w[0])) == 0;
    const auto face = static_cast<std::uint32_t>(f);
    // A planar polygon whose boundary is simple is one piece; one that is not
    // (it crosses or touches itself, e.g. a corner repeated) is fanned like a
    // non-planar one: the engines' documented rule where the spec is silent.
    if (planar && is_simple(flatten(w, n))) {
      proj.add(face, w, std::vector<Role>(w.size(), Role::Boundary), newell(w));
      continue;
    }
    // Non-planar (or not simple): fan from the first vertex; diagonals are inside the polygon.
    const std::size_t m = w.size();
    for (std::size_t i = 1; i + 1 < m; ++i) {
      V3 tn = cross3(sub(w[i], w[0]), sub(w[i + 1], w[0]));
      if (is_zero(tn)) continue;   // a flat fan triangle covers nothing
      std::vector<V3> tri{w[0], w[i], w[i + 1]};
      std::vector<Role> roles{i == 1 ? Role::Boundary : Role::Diagonal, Role::Boundary,
                              i + 2 == m ? Role::Boundary : Role::Diagonal};
      proj.add(face, tri, roles, tn);
    }
  }
  std::vector<Box> boxes;
  for (const Piece& p : out.pieces) boxes.push_back(p.box);
  out.grid.build(boxes);
  return out;
}

}  // namespace vismap_check
