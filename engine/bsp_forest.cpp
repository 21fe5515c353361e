#include "engine/bsp_forest.h"

#include <algorithm>
#include <numeric>
#include <optional>
#include <queue>

#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include "engine/union_find.h"
#include "engine/world_exact.h"

namespace vismap::engine {
namespace {

using Box = std::array<double, 6>;

// The plane (axis -1) through p with normal (q - p) x (s - r), for telling the
// sides of many points: the normal is made once, as intervals (their result is
// exact where no rounding happened: a zero in an axis-aligned scene needs no
// more) and, only where they cannot tell, in Mpzf (no gcd). Sides are taken
// under upward rounding, which the caller holds.
class PlaneSides {
 public:
  PlaneSides(const Scene& scene, const Separation& s)
      : p_(scene.vertices[s.ids[0]]), q_(scene.vertices[s.ids[1]]), r_(scene.vertices[s.ids[2]]),
        t_(scene.vertices[s.ids[3]]) {
    const I ux = I(q_.x) - p_.x, uy = I(q_.y) - p_.y, uz = I(q_.z) - p_.z;
    const I vx = I(t_.x) - r_.x, vy = I(t_.y) - r_.y, vz = I(t_.z) - r_.z;
    n_ = {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
  }

  // sign(det(q - p, s - r, x - p)).
  int operator()(const Vec3& x) {
    const I d = n_[0] * (I(x.x) - p_.x) + n_[1] * (I(x.y) - p_.y) + n_[2] * (I(x.z) - p_.z);
    if (d.inf() > 0) return 1;
    if (d.sup() < 0) return -1;
    if (d.inf() == 0 && d.sup() == 0) return 0;
    CGAL::Protect_FPU_rounding<true> nearest(CGAL_FE_TONEAREST);
    if (!exact_) {
      const M ux = M(q_.x) - M(p_.x), uy = M(q_.y) - M(p_.y), uz = M(q_.z) - M(p_.z);
      const M vx = M(t_.x) - M(r_.x), vy = M(t_.y) - M(r_.y), vz = M(t_.z) - M(r_.z);
      exact_ = std::array<M, 3>{uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
    }
    const std::array<M, 3>& n = *exact_;
    return (n[0] * (M(x.x) - M(p_.x)) + n[1] * (M(x.y) - M(p_.y)) + n[2] * (M(x.z) - M(p_.z))).sign();
  }

 private:
  using I = CGAL::Interval_nt<false>;
  using M = CGAL::Mpzf;
  const Vec3 &p_, &q_, &r_, &t_;
  std::array<I, 3> n_;
  std::optional<std::array<M, 3>> exact_;
};

bool boxes_meet(const Box& a, const Box& b) {
  for (int k = 0; k < 3; ++k)
    if (a[k + 3] < b[k] || b[k + 3] < a[k]) return false;
  return true;
}

// Facets joined where they share a vertex: the scene's objects, numbered by
// their first facet.
std::vector<std::vector<std::uint32_t>> objects_of(const WorldFacets& wf, std::size_t nvertices) {
  const auto n = wf.facets.size();
  UnionFind uf(n);
  std::vector<std::int64_t> first(nvertices, -1);
  for (std::size_t f = 0; f < n; ++f)
    for (auto id : wf.facets[f].v) {
      if (first[id] < 0) first[id] = static_cast<std::int64_t>(f);
      else uf.join(static_cast<int>(first[id]), static_cast<int>(f));
    }
  std::vector<int> number(n, -1);
  std::vector<std::vector<std::uint32_t>> out;
  for (std::size_t f = 0; f < n; ++f) {
    const int r = uf.find(static_cast<int>(f));
    if (number[r] < 0) {
      number[r] = static_cast<int>(out.size());
      out.emplace_back();
    }
    out[static_cast<std::size_t>(number[r])].push_back(static_cast<std::uint32_t>(f));
  }
  return out;
}

class ForestBuilder {
 public:
  ForestBuilder(const Scene& scene, BspForest& forest) : scene_(scene), f_(forest) {}

  // Groups merged until every two whose boxes meet have a separating plane.
  void group() {
    f_.groups = objects_of(*f_.facets, scene_.vertices.size());
    f_.objects = static_cast<std::int64_t>(f_.groups.size());
    for (;;) {
      boxes();
      f_.meeting.clear();
      UnionFind uf(f_.groups.size());
      bool merged = false;
      for (const auto& [g, h] : meeting_pairs()) {
        Separation s;
        if (separate(g, h, s)) f_.meeting[{g, h}] = s;
        else {
          uf.join(g, h);
          merged = true;
        }
      }
      if (!merged) return;
      merge(uf);
    }
  }

  void plant() {
    f_.group_of.assign(f_.facets->facets.size(), 0);
    for (std::size_t g = 0; g < f_.groups.size(); ++g) {
      for (auto fi : f_.groups[g]) f_.group_of[fi] = static_cast<std::uint32_t>(g);
      f_.trees.push_back(build_bsp_tree(scene_, f_.facets, f_.groups[g]));
    }
  }

 private:
  const Scene& scene_;
  BspForest& f_;
  std::vector<std::vector<std::uint32_t>> vertices_;   // each group's vertex ids

  void boxes() {
    f_.box.assign(f_.groups.size(), Box{HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL});
    vertices_.assign(f_.groups.size(), {});
    for (std::size_t g = 0; g < f_.groups.size(); ++g) {
      auto& vs = vertices_[g];
      for (auto fi : f_.groups[g])
        for (auto id : f_.facets->facets[fi].v) vs.push_back(id);
      std::sort(vs.begin(), vs.end());
      vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
      Box& b = f_.box[g];
      for (auto id : vs) {
        const Vec3& p = scene_.vertices[id];
        const double c[3] = {p.x, p.y, p.z};
        for (int k = 0; k < 3; ++k) {
          b[k] = std::min(b[k], c[k]);
          b[k + 3] = std::max(b[k + 3], c[k]);
        }
      }
    }
  }

  // Pairs g < h whose boxes meet (closed), by a sweep along x.
  std::vector<std::pair<int, int>> meeting_pairs() const {
    std::vector<int> by_x(f_.groups.size());
    std::iota(by_x.begin(), by_x.end(), 0);
    std::sort(by_x.begin(), by_x.end(), [&](int a, int b) { return f_.box[a][0] < f_.box[b][0] || (f_.box[a][0] == f_.box[b][0] && a < b); });
    std::vector<std::pair<int, int>> out;
    for (std::size_t i = 0; i < by_x.size(); ++i)
      for (std::size_t j = i + 1; j < by_x.size() && f_.box[by_x[j]][0] <= f_.box[by_x[i]][3]; ++j)
        if (boxes_meet(f_.box[by_x[i]], f_.box[by_x[j]]))
          out.emplace_back(std::min(by_x[i], by_x[j]), std::max(by_x[i], by_x[j]));
    std::sort(out.begin(), out.end());
    return out;
  }

  // A plane with g on one closed side and h strictly on the other (or the
  // reverse): a facet plane of either, else a plane through an edge of one
  // parallel to an edge of the other (for groups of few edges).
  bool separate(int g, int h, Separation& s) const {
    // The larger group's facet planes only where it is small too: a large group
    // (the walls and slabs of a whole building) rarely has a plane clear of a
    // small one inside its box, and each of its planes scanned against its own
    // vertices made the grouping quadratic (a generated building of 29 040
    // faces: 430 s). Left unseparated, the two share one tree: always right.
    constexpr std::size_t kAllPlanesUpTo = 256;
    const std::size_t ng = f_.groups[static_cast<std::size_t>(g)].size(), nh = f_.groups[static_cast<std::size_t>(h)].size();
    auto facet_plane_splits = [&](int owner) {
      for (auto fi : f_.groups[static_cast<std::size_t>(owner)]) {
        const std::array<std::uint32_t, 3> span = spanning_ids(scene_, f_.facets->facets[fi]);
        s.ids = {span[0], span[1], span[0], span[2]};
        if (splits(g, h, s)) return true;
      }
      return false;
    };
    if (facet_plane_splits(ng <= nh ? g : h)) return true;
    if (std::max(ng, nh) > kAllPlanesUpTo) return false;   // (nor edge planes: edges() sorts a group's edges)
    if (facet_plane_splits(ng <= nh ? h : g)) return true;
    const auto eg = edges(g), eh = edges(h);
    if (eg.size() * eh.size() > 4096) return false;   // (left to one group's tree)
    for (const auto& a : eg)
      for (const auto& b : eh) {
        s.ids = {a[0], a[1], b[0], b[1]};
        if (!parallel(s) && splits(g, h, s)) return true;
      }
    return false;
  }

  // Whether the plane s.ids has one group on a closed side and the other
  // strictly on the other; then s.first_side is g's side.
  bool splits(int g, int h, Separation& s) const {
    s.axis = -1;
    const int sg = sides(g, s), sh = sides(h, s);
    // (sides: bit 1 positive, bit 2 negative; 4 a vertex in the plane)
    auto closed = [](int x, int bit) { return (x & 3) == bit || (x & 3) == 0; };
    auto strict = [](int x, int bit) { return (x & 3) == bit && !(x & 4); };
    for (int bit : {1, 2}) {
      const int other = 3 - bit;
      if ((closed(sg, bit) && strict(sh, other)) || (strict(sg, bit) && closed(sh, other))) {
        s.first_side = bit == 1 ? 1 : -1;
        return true;
      }
    }
    return false;
  }

  // Edges p-q parallel to r-s give no plane: (q - p) x (s - r) = 0, exactly
  // (differences of doubles in Mpzf).
  bool parallel(const Separation& s) const {
    using M = CGAL::Mpzf;
    const Vec3 &p = scene_.vertices[s.ids[0]], &q = scene_.vertices[s.ids[1]];
    const Vec3 &r = scene_.vertices[s.ids[2]], &t = scene_.vertices[s.ids[3]];
    const M ux = M(q.x) - M(p.x), uy = M(q.y) - M(p.y), uz = M(q.z) - M(p.z);
    const M vx = M(t.x) - M(r.x), vy = M(t.y) - M(r.y), vz = M(t.z) - M(r.z);
    return (uy * vz - uz * vy).sign() == 0 && (uz * vx - ux * vz).sign() == 0 && (ux * vy - uy * vx).sign() == 0;
  }

  // The group's edges (vertex id pairs, each once).
  std::vector<std::array<std::uint32_t, 2>> edges(int g) const {
    std::vector<std::array<std::uint32_t, 2>> out;
    for (auto fi : f_.groups[static_cast<std::size_t>(g)]) {
      const auto& v = f_.facets->facets[fi].v;
      for (std::size_t k = 0; k < v.size(); ++k)
        out.push_back({std::min(v[k], v[(k + 1) % v.size()]), std::max(v[k], v[(k + 1) % v.size()])});
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  int sides(int g, const Separation& plane) const {
    CGAL::Protect_FPU_rounding<true> upward;
    PlaneSides side(scene_, plane);
    int s = 0;
    for (auto id : vertices_[static_cast<std::size_t>(g)]) {
      const int o3 = side(scene_.vertices[id]);
      s |= o3 > 0 ? 1 : o3 < 0 ? 2 : 4;
      if ((s & 3) == 3) break;
    }
    return s;
  }

  void merge(UnionFind& uf) {
    std::vector<int> number(f_.groups.size(), -1);
    std::vector<std::vector<std::uint32_t>> out;
    for (std::size_t g = 0; g < f_.groups.size(); ++g) {
      const int r = uf.find(static_cast<int>(g));
      if (number[r] < 0) {
        number[r] = static_cast<int>(out.size());
        out.emplace_back();
      }
      auto& m = out[static_cast<std::size_t>(number[r])];
      m.insert(m.end(), f_.groups[g].begin(), f_.groups[g].end());
    }
    for (auto& m : out) std::sort(m.begin(), m.end());
    f_.groups = std::move(out);
  }
};

// The plane between groups g < h whose boxes do not meet: an axis plane at the
// end of one box, the other strictly beyond.
Separation axis_separation(const Box& g, const Box& h) {
  Separation s;
  for (int k = 0; k < 3; ++k) {
    s.axis = k;
    if (g[k + 3] < h[k]) {   // g at or below c = g's top, h strictly above
      s.c = g[k + 3];
      s.first_side = -1;
      return s;
    }
    if (h[k + 3] < g[k]) {
      s.c = h[k + 3];
      s.first_side = 1;
      return s;
    }
  }
  s.axis = -2;   // (not reached: the boxes meet)
  return s;
}

// The side of the separating plane the eye is on (0: in it), exactly.
int eye_side_of(const Separation& s, const Scene& scene, const Eye& eye) {
  if (s.axis < 0) {
    const auto& v = scene.vertices;
    return eye_side(v[s.ids[0]], v[s.ids[1]], v[s.ids[2]], v[s.ids[3]], eye);
  }
  // x_axis - c at the eye (x, y, z, w): the sign of h[axis] - w c.
  return sgn(eye.h[static_cast<std::size_t>(s.axis)] - eye.h[3] * mpq_class(s.c));
}

// Strongly connected components of a graph (iterative Tarjan): comp[v], and
// the number of components.
int components(const std::vector<std::vector<int>>& next, std::vector<int>& comp) {
  const int n = static_cast<int>(next.size());
  comp.assign(static_cast<std::size_t>(n), -1);
  std::vector<int> index(static_cast<std::size_t>(n), -1), low(static_cast<std::size_t>(n), 0), stack;
  std::vector<char> on(static_cast<std::size_t>(n), 0);
  int counter = 0, count = 0;
  std::vector<std::pair<int, std::size_t>> call;
  for (int s = 0; s < n; ++s) {
    if (index[s] >= 0) continue;
    call.push_back({s, 0});
    while (!call.empty()) {
      auto& [v, i] = call.back();
      if (i == 0) {
        index[v] = low[v] = counter++;
        stack.push_back(v);
        on[v] = 1;
      }
      if (i < next[v].size()) {
        const int w = next[v][i++];
        if (index[w] < 0) call.push_back({w, 0});
        else if (on[w]) low[v] = std::min(low[v], index[w]);
        continue;
      }
      if (low[v] == index[v]) {
        for (;;) {
          const int w = stack.back();
          stack.pop_back();
          on[w] = 0;
          comp[w] = count;
          if (w == v) break;
        }
        ++count;
      }
      const int done = v;
      call.pop_back();
      if (!call.empty()) low[call.back().first] = std::min(low[call.back().first], low[done]);
    }
  }
  return count;
}

}  // namespace

BspForest build_bsp_forest(const Scene& scene, int threads) {
  const exact::FilterCounts before = exact::filter_counts;
  BspForest forest;
  forest.facets = std::make_shared<const WorldFacets>(make_world_facets(scene, threads));
  ForestBuilder b(scene, forest);
  b.group();
  b.plant();
  forest.counted = {exact::filter_counts.calls - before.calls, exact::filter_counts.exact - before.exact};
  return forest;
}

std::vector<const BspTree*> trees_back_to_front(BspForest& forest, const Scene& scene, const Eye& eye,
                                                const std::vector<std::array<double, 4>>& screen, Stats& stats) {
  const int n = static_cast<int>(forest.groups.size());
  // Groups whose screen bounds overlap, ordered by their plane: edges from the
  // group drawn first to the one drawn after.
  std::vector<int> shown;
  for (int g = 0; g < n; ++g)
    if (screen[static_cast<std::size_t>(g)][0] <= screen[static_cast<std::size_t>(g)][2]) shown.push_back(g);
  std::sort(shown.begin(), shown.end(), [&](int a, int b) { return screen[a][0] < screen[b][0] || (screen[a][0] == screen[b][0] && a < b); });
  std::vector<std::vector<int>> next(static_cast<std::size_t>(n));
  std::int64_t pairs = 0;
  for (std::size_t i = 0; i < shown.size(); ++i)
    for (std::size_t j = i + 1; j < shown.size() && screen[shown[j]][0] <= screen[shown[i]][2]; ++j) {
      const int g = std::min(shown[i], shown[j]), h = std::max(shown[i], shown[j]);
      if (screen[g][3] < screen[h][1] || screen[h][3] < screen[g][1]) continue;
      ++pairs;
      const auto met = forest.meeting.find({g, h});
      const Separation s = met != forest.meeting.end() ? met->second : axis_separation(forest.box[g], forest.box[h]);
      const int e = eye_side_of(s, scene, eye);
      if (e == 0) continue;   // (the eye in the plane: their projections only touch)
      // The group on the eye's side is drawn after the other.
      if (e == s.first_side) next[static_cast<std::size_t>(h)].push_back(g);
      else next[static_cast<std::size_t>(g)].push_back(h);
    }
  stats.count("priority_pairs", pairs);
  // Cycles: their groups drawn together; the order of the rest from the graph of
  // components (Kahn's, the lowest-numbered first among the ready: deterministic).
  std::vector<int> comp;
  const int nc = components(next, comp);
  std::vector<std::vector<int>> members(static_cast<std::size_t>(nc));
  for (int g = 0; g < n; ++g) members[static_cast<std::size_t>(comp[g])].push_back(g);
  std::vector<std::vector<int>> after(static_cast<std::size_t>(nc));
  std::vector<int> before(static_cast<std::size_t>(nc), 0);
  for (int g = 0; g < n; ++g)
    for (int h : next[static_cast<std::size_t>(g)])
      if (comp[g] != comp[h]) {
        after[static_cast<std::size_t>(comp[g])].push_back(comp[h]);
        ++before[static_cast<std::size_t>(comp[h])];
      }
  std::priority_queue<std::pair<int, int>, std::vector<std::pair<int, int>>, std::greater<>> ready;   // (first group, comp)
  for (int c = 0; c < nc; ++c)
    if (before[static_cast<std::size_t>(c)] == 0) ready.push({members[static_cast<std::size_t>(c)][0], c});
  std::vector<const BspTree*> out;
  std::int64_t circuits = 0;
  while (!ready.empty()) {
    const int c = ready.top().second;
    ready.pop();
    const std::vector<int>& m = members[static_cast<std::size_t>(c)];
    if (m.size() == 1) {
      out.push_back(&forest.trees[static_cast<std::size_t>(m[0])]);
    } else {
      ++circuits;
      // (A cycle's tree is made once, by the first view that meets it: other
      // views wait. The map's nodes stay where they are as others are added.)
      std::lock_guard<std::mutex> hold(*forest.circuits_lock);
      auto it = forest.circuits.find(m);
      if (it == forest.circuits.end()) {
        std::vector<std::uint32_t> facets;
        for (int g : m) facets.insert(facets.end(), forest.groups[static_cast<std::size_t>(g)].begin(),
                                      forest.groups[static_cast<std::size_t>(g)].end());
        std::sort(facets.begin(), facets.end());
        it = forest.circuits.emplace(m, build_bsp_tree(scene, forest.facets, facets)).first;
      } else {   // (made for an earlier view: counted as if made for this one)
        exact::filter_counts.calls += it->second.counted.calls;
        exact::filter_counts.exact += it->second.counted.exact;
      }
      out.push_back(&it->second);
    }
    for (int d : after[static_cast<std::size_t>(c)])
      if (--before[static_cast<std::size_t>(d)] == 0) ready.push({members[static_cast<std::size_t>(d)][0], d});
  }
  stats.count("priority_circuits", circuits);
  return out;
}

}  // namespace vismap::engine
