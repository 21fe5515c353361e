#include "engine/world_facets.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <gmpxx.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <optional>
#include <stdexcept>

#include "engine/holed_faces.h"
#include "engine/input_polygon.h"
#include "engine/parallel.h"
#include "engine/world_exact.h"

namespace vismap::engine {
namespace {

// Inputs are doubles, so Epick's filtered predicates are exact on them.
using KI = CGAL::Epick;

// Convex and simple: every turn has the same sign (straight turns allowed) and the
// boundary winds once (edge directions change x-sign at most twice).
bool is_convex(const std::vector<Q2>& q, CGAL::Orientation& turn) {
  const std::size_t n = q.size();
  turn = CGAL::COLLINEAR;
  for (std::size_t i = 0; i < n; ++i) {
    auto o = CGAL::orientation(q[i], q[(i + 1) % n], q[(i + 2) % n]);
    if (o == CGAL::COLLINEAR) {
      // A straight vertex is fine unless the boundary folds back on itself.
      const Q2 &a = q[i], &b = q[(i + 1) % n], &c = q[(i + 2) % n];
      // (b - a).(c - b) < 0, decided exactly (in doubles, tiny coordinates underflow).
      if (CGAL::angle(a, b, c) == CGAL::ACUTE) return false;
      continue;
    }
    if (turn == CGAL::COLLINEAR) turn = o;
    else if (o != turn) return false;
  }
  int changes = 0, last = 0;
  for (std::size_t i = 0; i <= n; ++i) {
    const Q2 &a = q[i % n], &b = q[(i + 1) % n];
    int s = CGAL::compare(a.x(), b.x());
    if (s == 0) continue;
    if (last != 0 && s != last) ++changes;
    last = s;
  }
  return turn != CGAL::COLLINEAR && changes <= 2;
}

// Ear clipping with exact predicates. Returns false when no ear is found (a
// self-intersecting polygon), in which case the caller falls back to a fan.
bool ear_clip(const std::vector<Q2>& q, CGAL::Orientation turn,
              std::vector<std::array<std::size_t, 3>>& tris) {
  std::vector<std::size_t> idx(q.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  while (idx.size() > 3) {
    bool found = false;
    for (std::size_t k = 0; k < idx.size() && !found; ++k) {
      std::size_t ia = idx[(k + idx.size() - 1) % idx.size()], ib = idx[k], ic = idx[(k + 1) % idx.size()];
      if (CGAL::orientation(q[ia], q[ib], q[ic]) != turn) continue;
      bool empty = true;
      for (std::size_t j : idx) {
        if (j == ia || j == ib || j == ic) continue;
        // A vertex inside or on the candidate ear blocks it.
        auto o1 = CGAL::orientation(q[ia], q[ib], q[j]), o2 = CGAL::orientation(q[ib], q[ic], q[j]),
             o3 = CGAL::orientation(q[ic], q[ia], q[j]);
        if (o1 != -turn && o2 != -turn && o3 != -turn) { empty = false; break; }
      }
      if (!empty) continue;
      tris.push_back({ia, ib, ic});
      idx.erase(idx.begin() + k);
      found = true;
    }
    if (!found) return false;
  }
  if (CGAL::orientation(q[idx[0]], q[idx[1]], q[idx[2]]) != CGAL::COLLINEAR)
    tris.push_back({idx[0], idx[1], idx[2]});
  return true;
}

// A triangle (a, b, c) of polygon positions; an edge is the polygon's own when its
// end points are consecutive around the polygon.
WorldFacet triangle_facet(int face, const std::vector<std::uint32_t>& ids, std::size_t n,
                          std::size_t a, std::size_t b, std::size_t c) {
  auto role = [n](std::size_t i, std::size_t j) {
    return (j == (i + 1) % n) ? EdgeRole::Boundary : EdgeRole::Internal;
  };
  return WorldFacet{face, true, false, {ids[a], ids[b], ids[c]}, {role(a, b), role(b, c), role(c, a)}};
}

}  // namespace

std::vector<std::uint32_t> canonical_vertex_ids(const Scene& scene, int threads) {
  // Open addressing over a power-of-two table (no node per vertex), filled side
  // by side: a slot, once taken, keeps one point's coordinates, and the least
  // index among its equal vertices (an atomic minimum), as one pass in index
  // order would leave it; each vertex notes its point's slot (in its place in
  // the answer), then reads what the slot holds when every vertex is in.
  auto bits = [](double d) {
    d += 0.0;   // -0 == +0
    std::uint64_t b;
    std::memcpy(&b, &d, sizeof b);
    return b;
  };
  auto hash = [&](const Vec3& p) {
    std::uint64_t h = bits(p.x) * 0x9E3779B97F4A7C15ull;
    h = (h ^ (h >> 29) ^ bits(p.y)) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 31) ^ bits(p.z)) * 0x94D049BB133111EBull;
    return h ^ (h >> 32);
  };
  const std::size_t n = scene.vertices.size();
  // (Vertex ids, and the slots of a table of at most 2^32, are 32-bit.)
  if (n >= std::size_t{1} << 31) throw std::invalid_argument("the scene has 2^31 vertices or more (vertex ids are 32-bit)");
  std::size_t cap = 16;
  while (cap < 2 * n) cap *= 2;
  constexpr std::uint32_t empty = 0xffffffffu;
  std::vector<std::uint32_t> table(cap, empty);
  auto same = [&](const Vec3& p, std::uint32_t j) {
    const Vec3& q = scene.vertices[j];
    return p.x == q.x && p.y == q.y && p.z == q.z;
  };
  std::vector<std::uint32_t> canon(n);   // (first each vertex's slot)
  parallel_chunks(static_cast<int>(n), 16384, threads, [&](int, Chunk r) {
    for (auto i = static_cast<std::uint32_t>(r.begin); i < static_cast<std::uint32_t>(r.end); ++i) {
      const Vec3& p = scene.vertices[i];
      for (std::size_t k = hash(p) & (cap - 1);; k = (k + 1) & (cap - 1)) {
        canon[i] = static_cast<std::uint32_t>(k);
        std::uint32_t held = empty;
        if (shared_compare_exchange(table[k], held, i, threads)) break;   // (taken by i)
        if (!same(p, held)) continue;
        while (i < held && !shared_compare_exchange(table[k], held, i, threads)) {}
        break;
      }
    }
  });
  parallel_chunks(static_cast<int>(n), 16384, threads, [&](int, Chunk r) {
    for (auto i = static_cast<std::size_t>(r.begin); i < static_cast<std::size_t>(r.end); ++i) canon[i] = table[canon[i]];
  });
  return canon;
}

namespace {

// A face of three distinct corners not in a line (most faces of a mesh) made
// its facet straight away, as the general path below would make it; false
// (nothing made) for any other face.
bool is_plain_triangle(const Scene& scene, const std::vector<std::uint32_t>& canon, const IndexRing& ring,
                       int face, WorldFacets& out) {
  if (ring.size() != 3) return false;
  const std::uint32_t a = canon[ring[0]], b = canon[ring[1]], c = canon[ring[2]];
  if (a == b || b == c || c == a) return false;   // (canonical: equal ids for equal points only)
  const Vec3 &pa = scene.vertices[a], &pb = scene.vertices[b], &pc = scene.vertices[c];
  if (CGAL::collinear(Q3(pa.x, pa.y, pa.z), Q3(pb.x, pb.y, pb.z), Q3(pc.x, pc.y, pc.z))) return false;
  out.facets.push_back(WorldFacet{face, true, false, {a, b, c}, {EdgeRole::Boundary, EdgeRole::Boundary, EdgeRole::Boundary}});
  return true;
}

// Faces [r.begin, r.end) into `out`, in order (with their counts).
void facets_of_faces(const Scene& scene, const std::vector<std::uint32_t>& canon, Chunk r, WorldFacets& out) {
  std::vector<std::uint32_t> ids;
  std::vector<Q3> p;
  for (std::size_t f = static_cast<std::size_t>(r.begin); f < static_cast<std::size_t>(r.end); ++f) {
    if (!scene.holes_of(f).empty()) {
      facets_of_holed_face(scene, canon, f, out);
      continue;
    }
    if (is_plain_triangle(scene, canon, scene.faces[f], static_cast<int>(f), out)) continue;
    distinct_corners(scene, canon, scene.faces[f], ids, p);
    std::size_t i1, i2;
    if (!find_plane(p, i1, i2)) { ++out.degenerate; continue; }
    const int face = static_cast<int>(f);
    auto keep_whole = [&] {   // (the polygon is one convex facet)
      out.facets.push_back(WorldFacet{face, true, false, SmallVec<std::uint32_t, 4>(ids.begin(), ids.end()),
                                      SmallVec<EdgeRole, 8>(ids.size(), EdgeRole::Boundary)});
    };
    if (p.size() == 3) {   // (three corners not in a line: planar and convex, nothing to test)
      keep_whole();
      continue;
    }
    bool planar = true;
    // (The three points that span the plane lie in it: no exact zero to compute.)
    for (std::size_t k = 1; k < p.size() && planar; ++k)
      planar = k == i1 || k == i2 || CGAL::orientation(p[0], p[i1], p[i2], p[k]) == CGAL::COPLANAR;
    const std::size_t n = p.size();
    if (planar) {
      int axis = dominant_axis(p[0], p[i1], p[i2]);
      std::vector<Q2> q(n);
      for (std::size_t k = 0; k < n; ++k) q[k] = drop_axis(p[k], axis);
      CGAL::Orientation turn;
      if (is_convex(q, turn)) {
        keep_whole();
        continue;
      }
      ++out.nonconvex;
      // The polygon's orientation (exact sign of its area) decides which turn is an ear.
      mpq_class area2 = 0;
      for (std::size_t k = 0; k < n; ++k) {
        const Q2 &a = q[k], &b = q[(k + 1) % n];
        area2 += mpq_class(a.x()) * b.y() - mpq_class(b.x()) * a.y();
      }
      const int area_sign = sgn(area2);
      std::vector<std::array<std::size_t, 3>> tris;
      // A boundary that is not simple (crossing or touching itself) is fanned.
      if (area_sign != 0 && is_simple_ring(q) && ear_clip(q, area_sign > 0 ? CGAL::LEFT_TURN : CGAL::RIGHT_TURN, tris)) {
        for (auto& t : tris) {
          out.facets.push_back(triangle_facet(face, ids, n, t[0], t[1], t[2]));
          out.facets.back().split = true;
        }
        continue;
      }
    } else {
      ++out.nonplanar;
    }
    // Fan from the first vertex; collinear pieces of the fan cover nothing.
    for (std::size_t k = 1; k + 1 < n; ++k)
      if (!CGAL::collinear(p[0], p[k], p[k + 1])) {
        out.facets.push_back(triangle_facet(face, ids, n, 0, k, k + 1));
        out.facets.back().planar = planar;
      }
  }
}

}  // namespace

void distinct_corners(const Scene& scene, const std::vector<std::uint32_t>& canon, const IndexRing& ring,
                      std::vector<std::uint32_t>& ids, std::vector<Q3>& p) {
  ids.clear();
  p.clear();
  for (std::uint32_t i : ring) {
    i = canon[i];
    const Vec3& v = scene.vertices[i];
    const Q3 x(v.x, v.y, v.z);
    if (!p.empty() && p.back() == x) continue;
    ids.push_back(i);
    p.push_back(x);
  }
  while (p.size() > 1 && p.back() == p.front()) { p.pop_back(); ids.pop_back(); }
}

bool find_plane(const std::vector<Q3>& p, std::size_t& i1, std::size_t& i2) {
  if (p.size() < 3) return false;
  for (i1 = 1; i1 < p.size() && p[i1] == p[0]; ++i1) {}
  for (i2 = i1 + 1; i2 < p.size(); ++i2)
    if (!CGAL::collinear(p[0], p[i1], p[i2])) return true;
  return false;
}

int dominant_axis(const Q3& a, const Q3& b, const Q3& c) {
  // Orientation of the projections onto the yz, zx, xy planes are the signs of the
  // normal's components; pick the first axis whose projection is not degenerate,
  // preferring the one with the largest magnitude in doubles (any non-zero works).
  double nx = (b.y() - a.y()) * (c.z() - a.z()) - (b.z() - a.z()) * (c.y() - a.y());
  double ny = (b.z() - a.z()) * (c.x() - a.x()) - (b.x() - a.x()) * (c.z() - a.z());
  double nz = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  int order[3] = {0, 1, 2};
  double mag[3] = {std::abs(nx), std::abs(ny), std::abs(nz)};
  std::sort(order, order + 3, [&](int i, int j) { return mag[i] > mag[j]; });
  for (int axis : order)
    if (CGAL::orientation(drop_axis(a, axis), drop_axis(b, axis), drop_axis(c, axis)) != CGAL::COLLINEAR) return axis;
  return 2;  // unreachable for non-collinear a, b, c
}

Q2 drop_axis(const Q3& p, int axis) {
  return axis == 0 ? Q2(p.y(), p.z()) : axis == 1 ? Q2(p.z(), p.x()) : Q2(p.x(), p.y());
}

bool is_simple_ring(const std::vector<Q2>& q) {
  const std::size_t n = q.size();
  auto lo = [&](std::size_t i) { return std::min(q[i].x(), q[(i + 1) % n].x()); };
  auto hi = [&](std::size_t i) { return std::max(q[i].x(), q[(i + 1) % n].x()); };
  // Edges i < j: do they meet anywhere but where neighbours must?
  auto meet = [&](std::size_t i, std::size_t j) {
    if (j == i + 1 || (i == 0 && j == n - 1)) {
      // Neighbours: the far end of one must not lie on the other, past their corner.
      const Q2& corner = j == i + 1 ? q[j] : q[0];
      const Q2& far_i = j == i + 1 ? q[i] : q[1];
      const Q2& far_j = j == i + 1 ? q[(j + 1) % n] : q[j];
      return CGAL::collinear(far_i, corner, far_j) && CGAL::angle(far_i, corner, far_j) == CGAL::ACUTE;
    }
    return CGAL::do_intersect(KI::Segment_2(q[i], q[(i + 1) % n]), KI::Segment_2(q[j], q[(j + 1) % n]));
  };
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo(a) < lo(b); });
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t i = order[a];
    const double end = hi(i);
    for (std::size_t b = a + 1; b < n && lo(order[b]) <= end; ++b) {
      const std::size_t j = order[b];
      if (meet(std::min(i, j), std::max(i, j))) return false;
    }
  }
  return true;
}


namespace {

// Each triangle's unit normal from its corners in order, which are its spanning
// corners (spanning_ids); unknown for the others. Chunks in parallel, in the
// input's order (a face's corners are mostly near the last face's in memory).
std::vector<world::UnitNormal> unit_normals(const Scene& scene, const std::vector<WorldFacet>& facets, int threads) {
  std::vector<world::UnitNormal> normals(facets.size());
  parallel_chunks(static_cast<int>(facets.size()), 8192, threads, [&](int, Chunk r) {
    for (auto f = static_cast<std::size_t>(r.begin); f < static_cast<std::size_t>(r.end); ++f) {
      const auto& v = facets[f].v;
      if (v.size() == 3) normals[f] = world::unit_normal(scene.vertices[v[0]], scene.vertices[v[1]], scene.vertices[v[2]]);
    }
  });
  return normals;
}

// Where every face is a triangle (most meshes): each face's facet made in its
// place, as is_plain_triangle makes it, with its unit normal (unit_normals'), on
// the threads: no chunk's facets moved again. A triangle that is not plain (its
// corners equal or in a line) is degenerate, as the general path finds it: its
// slot is dropped afterwards, counted. Nullopt where some face is not a triangle
// or has holes (the general path then). (The plain test is written out here,
// not shared: through a function that fills a slot or an optional, 10^6
// triangles took 15-20 ms longer.)
std::optional<WorldFacets> triangle_facets(const Scene& scene, const std::vector<std::uint32_t>& canon, int threads) {
  auto holed = [](const std::vector<IndexRing>& h) { return !h.empty(); };
  auto not_triangle = [](const IndexRing& ring) { return ring.size() != 3; };
  if (std::any_of(scene.holes.begin(), scene.holes.end(), holed) ||
      std::any_of(scene.faces.begin(), scene.faces.end(), not_triangle))
    return std::nullopt;
  const int n = static_cast<int>(scene.faces.size()), size = 4096;
  WorldFacets out;
  out.facets.reserve(scene.faces.size());
  fault_in_spare(out.facets, scene.faces.size(), threads);
  out.facets.resize(scene.faces.size());   // (face -1: a slot left empty)
  out.normals.resize(scene.faces.size());
  std::vector<std::int64_t> degenerate(static_cast<std::size_t>(chunk_count(n, size)), 0);
  parallel_chunks(n, size, threads, [&](int k, Chunk r) {
    for (int f = r.begin; f < r.end; ++f) {
      const IndexRing& ring = scene.faces[static_cast<std::size_t>(f)];
      const std::uint32_t a = canon[ring[0]], b = canon[ring[1]], c = canon[ring[2]];
      const Vec3 &pa = scene.vertices[a], &pb = scene.vertices[b], &pc = scene.vertices[c];
      if (a == b || b == c || c == a ||
          CGAL::collinear(Q3(pa.x, pa.y, pa.z), Q3(pb.x, pb.y, pb.z), Q3(pc.x, pc.y, pc.z))) {
        ++degenerate[static_cast<std::size_t>(k)];
        continue;
      }
      out.facets[static_cast<std::size_t>(f)] =
          WorldFacet{f, true, false, {a, b, c}, {EdgeRole::Boundary, EdgeRole::Boundary, EdgeRole::Boundary}};
      out.normals[static_cast<std::size_t>(f)] = world::unit_normal(pa, pb, pc);
    }
  });
  for (const std::int64_t d : degenerate) out.degenerate += d;
  if (out.degenerate == 0) return out;
  std::size_t kept = 0;   // (the empty slots dropped, the others in order)
  for (std::size_t f = 0; f < out.facets.size(); ++f) {
    if (out.facets[f].face < 0) continue;
    if (kept != f) {
      out.facets[kept] = std::move(out.facets[f]);
      out.normals[kept] = out.normals[f];
    }
    ++kept;
  }
  out.facets.resize(kept);
  out.normals.resize(kept);
  return out;
}

}  // namespace

WorldFacets make_world_facets(const Scene& scene, int threads) {
  const std::vector<std::uint32_t> canon = canonical_vertex_ids(scene, threads);
  if (std::optional<WorldFacets> triangles = triangle_facets(scene, canon, threads)) return std::move(*triangles);
  // Chunks of faces in parallel, joined in order (their counts beside them).
  const int nfaces = static_cast<int>(scene.faces.size()), size = 4096, chunks = chunk_count(nfaces, size);
  std::vector<WorldFacets> counts(static_cast<std::size_t>(chunks));
  // A bad face with holes throws; the first in face order is the one reported,
  // whatever the thread count.
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(chunks));
  WorldFacets out;
  out.facets.reserve(scene.faces.size());
  parallel_append(out.facets, chunks, threads, [&](int k, std::vector<WorldFacet>& facets) {
    WorldFacets c;
    c.facets.reserve(static_cast<std::size_t>(size));
    try {
      facets_of_faces(scene, canon, chunk(k, nfaces, size), c);
    } catch (...) {
      errors[static_cast<std::size_t>(k)] = std::current_exception();
    }
    facets = std::move(c.facets);
    counts[static_cast<std::size_t>(k)] = std::move(c);
  });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  for (const WorldFacets& c : counts) {
    out.degenerate += c.degenerate;
    out.nonplanar += c.nonplanar;
    out.nonconvex += c.nonconvex;
  }
  out.normals = unit_normals(scene, out.facets, threads);
  return out;
}

std::array<std::uint32_t, 3> spanning_ids(const Scene& scene, const WorldFacet& w) {
  const auto& v = w.v;
  // A triangle spans its plane, or nothing does (then its normal is zero from
  // any corners: a degenerate triangle is never an occluder, nor a crease).
  if (v.size() == 3) return {v[0], v[1], v[2]};
  const Vec3& o = scene.vertices[v[0]];
  for (std::size_t k = 1; k + 1 < v.size(); ++k) {
    const Vec3 &p = scene.vertices[v[k]], &q = scene.vertices[v[k + 1]];
    if (world::within(100, {&o, &p, &q})) {
      CGAL::Protect_FPU_rounding<true> upward;
      using Interval = CGAL::Interval_nt<false>;
      const auto n = world::normal_of<Interval>(o, p, q);
      if (std::any_of(n.begin(), n.end(), [](const Interval& x) { return x.inf() > 0 || x.sup() < 0; }))
        return {v[0], v[k], v[k + 1]};
    }
    const auto n = world::normal_of<CGAL::Mpzf>(o, p, q);
    if (n[0].sign() != 0 || n[1].sign() != 0 || n[2].sign() != 0) return {v[0], v[k], v[k + 1]};
  }
  return {v[0], v[0], v[0]};   // (a planar facet always has a spanning triple)
}


void number_by_first_use(const WorldFacets& wf, std::size_t nvertices, std::vector<std::uint32_t>& used,
                         std::vector<std::uint32_t>& local) {
  local.assign(nvertices, ~0u);
  used.clear();
  for (const auto& f : wf.facets)
    for (auto id : f.v)
      if (local[id] == ~0u) {
        local[id] = static_cast<std::uint32_t>(used.size());
        used.push_back(id);
      }
}

}  // namespace vismap::engine
