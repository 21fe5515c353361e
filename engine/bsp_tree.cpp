#include "engine/bsp_tree.h"

#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>
#include <CGAL/gmpxx.h>

#include <algorithm>
#include <array>
#include <cstdlib>

#include "engine/part_edges.h"
#include "engine/world_exact.h"

namespace vismap::engine {
namespace {

using Interval = CGAL::Interval_nt<false>;

// A splitting plane: n . (X - o) = 0 with n = (a - o) x (b - o), o, a, b input
// vertices. Its normal in intervals (a filter for split points), exactly once a
// split needs the value.
struct Plane {
  const Vec3 *o, *a, *b;
  std::array<Interval, 3> ni;
  bool has_exact = false;
  std::array<mpq_class, 3> n;

  Plane(const Vec3& o_, const Vec3& a_, const Vec3& b_) : o(&o_), a(&a_), b(&b_) {
    CGAL::Protect_FPU_rounding<true> upward;
    ni = world::normal_of<Interval>(o_, a_, b_);
  }
  const std::array<mpq_class, 3>& exact() {
    if (!has_exact) {
      n = world::normal_of<mpq_class>(*o, *a, *b);
      has_exact = true;
    }
    return n;
  }
};

class Builder {
 public:
  explicit Builder(const Scene& scene, BspTree& t) : scene_(scene), t_(t) {}

  void run(const std::vector<std::uint32_t>& facets) {
    std::vector<std::uint32_t> all;
    for (std::uint32_t f : facets) {
      BspTree::Fragment x;
      x.facet = f;
      for (auto id : t_.facets->facets[f].v) {
        x.edge.push_back(static_cast<int>(x.corners.size()));
        x.corners.push_back(point_of_vertex(id));
      }
      all.push_back(static_cast<std::uint32_t>(t_.fragments.size()));
      t_.fragments.push_back(std::move(x));
    }
    // Subtrees to build: the fragments, and where the subtree's node goes.
    struct Task {
      std::vector<std::uint32_t> list;
      int parent;
      bool front;
      int depth;
    };
    std::vector<Task> todo;
    todo.push_back({std::move(all), -1, false, 1});
    while (!todo.empty()) {
      Task task = std::move(todo.back());
      todo.pop_back();
      if (task.list.empty()) continue;
      const int node = static_cast<int>(t_.nodes.size());
      if (task.parent < 0) t_.root = node;
      else if (task.front) t_.nodes[task.parent].front = node;
      else t_.nodes[task.parent].back = node;
      t_.depth = std::max(t_.depth, task.depth);
      std::vector<std::uint32_t> front, back;
      split_by(task.list, node, front, back);
      todo.push_back({std::move(back), node, false, task.depth + 1});
      todo.push_back({std::move(front), node, true, task.depth + 1});
    }
  }

 private:
  const Scene& scene_;
  BspTree& t_;
  std::vector<std::uint32_t> point_of_;                  // input vertex -> its point, or ~0u
  // Per point (unused for input vertices): its coordinates as intervals, and
  // the plane that cut it (spanning vertex ids). (Its segment: Point::a, b.)
  std::vector<std::array<Interval, 3>> split_interval_;
  std::vector<std::array<std::uint32_t, 3>> cut_by_;

  std::uint32_t point_of_vertex(std::uint32_t id) {
    if (point_of_.empty()) point_of_.assign(scene_.vertices.size(), ~0u);
    if (point_of_[id] == ~0u) {
      point_of_[id] = static_cast<std::uint32_t>(t_.points.size());
      BspTree::Point p;
      p.vertex = id;
      t_.points.push_back(p);
      split_interval_.emplace_back();
      cut_by_.emplace_back();
    }
    return point_of_[id];
  }

  // The side of point i: sign(n . (X - o)).
  int side(std::uint32_t i, Plane& pl) {
    const BspTree::Point& p = t_.points[i];
    if (p.vertex >= 0) return world::orientation(*pl.o, *pl.a, *pl.b, scene_.vertices[static_cast<std::size_t>(p.vertex)]);
    {
      CGAL::Protect_FPU_rounding<true> upward;
      const auto& xi = split_interval_[i];
      const Interval v = pl.ni[0] * (xi[0] - pl.o->x) + pl.ni[1] * (xi[1] - pl.o->y) + pl.ni[2] * (xi[2] - pl.o->z);
      if (v.inf() > 0) return 1;
      if (v.sup() < 0) return -1;
      if (v.inf() == 0 && v.sup() == 0) return 0;   // (the interval holds the value: exactly 0)
    }
    // In the plane, known without rationals (the commonest case on a mesh: a
    // point cut on an edge two facets share lies in both their planes): the plane
    // holds the segment it was cut from, or is the plane that cut it.
    if (side(p.a, pl) == 0 && side(p.b, pl) == 0) return 0;
    const auto& c = cut_by_[i];
    auto in_plane = [&](std::uint32_t id) { return world::orientation(*pl.o, *pl.a, *pl.b, scene_.vertices[id]) == 0; };
    if (in_plane(c[0]) && in_plane(c[1]) && in_plane(c[2])) return 0;
    return sgn(value(i, pl));
  }

  // n . (X - o), exactly.
  mpq_class value(std::uint32_t i, Plane& pl) {
    const auto& n = pl.exact();
    const BspTree::Point& p = t_.points[i];
    if (p.vertex >= 0) {
      const Vec3& v = scene_.vertices[static_cast<std::size_t>(p.vertex)];
      return n[0] * (mpq_class(v.x) - pl.o->x) + n[1] * (mpq_class(v.y) - pl.o->y) + n[2] * (mpq_class(v.z) - pl.o->z);
    }
    return n[0] * (p.x - pl.o->x) + n[1] * (p.y - pl.o->y) + n[2] * (p.z - pl.o->z);
  }

  std::array<mpq_class, 3> coordinates(std::uint32_t i) const {
    const BspTree::Point& p = t_.points[i];
    if (p.vertex < 0) return {p.x, p.y, p.z};
    const Vec3& v = scene_.vertices[static_cast<std::size_t>(p.vertex)];
    return {mpq_class(v.x), mpq_class(v.y), mpq_class(v.z)};
  }

  // Where the plane cuts segment p -> q (strictly between them: their sides differ).
  std::uint32_t cut_point(std::uint32_t p, std::uint32_t q, Plane& pl, const std::array<std::uint32_t, 3>& span) {
    const mpq_class vp = value(p, pl), vq = value(q, pl);
    const mpq_class t = vp / (vp - vq);
    const auto a = coordinates(p), b = coordinates(q);
    BspTree::Point x;
    x.a = p;
    x.b = q;
    x.t = t;
    x.x = a[0] + t * (b[0] - a[0]);
    x.y = a[1] + t * (b[1] - a[1]);
    x.z = a[2] + t * (b[2] - a[2]);
    split_interval_.push_back({Interval(CGAL::to_interval(x.x)), Interval(CGAL::to_interval(x.y)),
                               Interval(CGAL::to_interval(x.z))});
    cut_by_.push_back(span);
    t_.points.push_back(std::move(x));
    return static_cast<std::uint32_t>(t_.points.size() - 1);
  }

  std::array<std::uint32_t, 3> span_of(std::uint32_t f) const { return spanning_ids(scene_, t_.facets->facets[f]); }

  // Which sides of the plane fragment x has corners strictly on: 1 front, 2 back.
  int sides_of(const BspTree::Fragment& x, Plane& pl) {
    int s = 0;
    for (auto c : x.corners) {
      const int g = side(c, pl);
      s |= g > 0 ? 1 : g < 0 ? 2 : 0;
      if (s == 3) break;
    }
    return s;
  }

  // The splitter among a few candidates spread over the list: fewest fragments
  // cut, then the most even sides (the first such candidate).
  std::size_t choose_splitter(const std::vector<std::uint32_t>& list) {
    const std::size_t n = list.size(), k = std::min<std::size_t>(n, 5);
    std::size_t best = 0;
    std::int64_t best_score = -1;
    for (std::size_t c = 0; c < k && n > 1; ++c) {
      const std::size_t at = c * n / k;
      const auto span = span_of(t_.fragments[list[at]].facet);
      Plane pl(scene_.vertices[span[0]], scene_.vertices[span[1]], scene_.vertices[span[2]]);
      std::int64_t cut = 0, front = 0, back = 0;
      for (auto fi : list) {
        const int s = sides_of(t_.fragments[fi], pl);
        cut += s == 3;
        front += s == 1;
        back += s == 2;
      }
      const std::int64_t score = 8 * cut + std::llabs(front - back);
      if (best_score < 0 || score < best_score) {
        best_score = score;
        best = at;
      }
    }
    return best;
  }

  // Node `node` for the fragments of `list`: its plane, the fragments in it, and
  // the others (cut where they cross it) to the front and back lists.
  void split_by(const std::vector<std::uint32_t>& list, int node, std::vector<std::uint32_t>& front,
                std::vector<std::uint32_t>& back) {
    const auto span = span_of(t_.fragments[list[choose_splitter(list)]].facet);
    t_.nodes.emplace_back();
    std::copy(span.begin(), span.end(), t_.nodes[node].span);
    Plane pl(scene_.vertices[span[0]], scene_.vertices[span[1]], scene_.vertices[span[2]]);
    std::vector<int> sg;
    for (auto fi : list) {
      const BspTree::Fragment& x = t_.fragments[fi];
      sg.clear();
      int s = 0;
      for (auto c : x.corners) {
        sg.push_back(side(c, pl));
        s |= sg.back() > 0 ? 1 : sg.back() < 0 ? 2 : 0;
      }
      if (s == 0) t_.nodes[node].on.push_back(fi);
      else if (s == 1) front.push_back(fi);
      else if (s == 2) back.push_back(fi);
      else {
        auto [f, b] = cut(fi, sg, pl, span);
        front.push_back(f);
        back.push_back(b);
        ++t_.splits;
      }
    }
  }

  // Fragment fi cut by the plane (sg: its corners' sides): its front and back parts.
  std::pair<std::uint32_t, std::uint32_t> cut(std::uint32_t fi, const std::vector<int>& sg, Plane& pl,
                                              const std::array<std::uint32_t, 3>& span) {
    BspTree::Fragment f, b;
    f.facet = b.facet = t_.fragments[fi].facet;
    const std::vector<std::uint32_t> c = t_.fragments[fi].corners;   // (a copy: fi is overwritten)
    const std::vector<int> edge = t_.fragments[fi].edge;
    const std::size_t n = c.size();
    std::vector<std::uint64_t> f_on, b_on;   // which edges of the cut fragment each corner lies on
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t k1 = (k + 1) % n;
      if (sg[k] >= 0) { f.corners.push_back(c[k]); f_on.push_back(on_corner(k, n)); }
      if (sg[k] <= 0) { b.corners.push_back(c[k]); b_on.push_back(on_corner(k, n)); }
      if (sg[k] * sg[k1] < 0) {
        const std::uint32_t x = cut_point(c[k], c[k1], pl, span);
        f.corners.push_back(x);
        b.corners.push_back(x);
        f_on.push_back(on_edge(k));
        b_on.push_back(on_edge(k));
      }
    }
    f.edge = part_edges(f_on, edge);
    b.edge = part_edges(b_on, edge);
    // (The front part takes the cut fragment's place: the tree keeps only live fragments.)
    t_.fragments[fi] = std::move(f);
    t_.fragments.push_back(std::move(b));
    return {fi, static_cast<std::uint32_t>(t_.fragments.size() - 1)};
  }
};

}  // namespace

BspTree build_bsp_tree(const Scene& scene, std::shared_ptr<const WorldFacets> wf,
                       const std::vector<std::uint32_t>& facets) {
  const exact::FilterCounts before = exact::filter_counts;
  BspTree t;
  t.facets = std::move(wf);
  Builder(scene, t).run(facets);
  t.counted = {exact::filter_counts.calls - before.calls, exact::filter_counts.exact - before.exact};
  return t;
}

BspTree build_bsp_tree(const Scene& scene, int threads) {
  auto wf = std::make_shared<const WorldFacets>(make_world_facets(scene, threads));
  std::vector<std::uint32_t> all(wf->facets.size());
  for (std::uint32_t f = 0; f < all.size(); ++f) all[f] = f;
  return build_bsp_tree(scene, std::move(wf), all);
}

Eye eye_of(const View& view) {
  Eye e;
  auto q = [&](int r, int c) { return mpq_class(view.m[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)]); };
  if (view.perspective) {
    // The null vector of the rows X, Y, W (3 x 4): its components are the signed
    // 3 x 3 minors.
    const int rows[3] = {0, 1, 3};
    for (int j = 0; j < 4; ++j) {
      int c[3], k = 0;
      for (int col = 0; col < 4; ++col)
        if (col != j) c[k++] = col;
      auto m = [&](int i, int l) { return q(rows[i], c[l]); };
      const mpq_class minor = m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) -
                              m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
                              m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
      e.h[static_cast<std::size_t>(j)] = j % 2 == 0 ? minor : mpq_class(-minor);
    }
    if (sgn(e.h[3]) < 0)
      for (auto& x : e.h) x = -x;
  } else {
    // r x u, turned against depth (d . (r x u) > 0 for the view's frame; its sign is taken).
    const mpq_class wx = q(0, 1) * q(1, 2) - q(0, 2) * q(1, 1), wy = q(0, 2) * q(1, 0) - q(0, 0) * q(1, 2),
                    wz = q(0, 0) * q(1, 1) - q(0, 1) * q(1, 0);
    const int s = sgn(q(2, 0) * wx + q(2, 1) * wy + q(2, 2) * wz) >= 0 ? -1 : 1;
    e.h = {s * wx, s * wy, s * wz, mpq_class(0)};
  }
  for (std::size_t j = 0; j < 4; ++j) {
    const auto i = CGAL::to_interval(e.h[j]);
    e.near[j] = {i.first, i.second};
  }
  return e;
}

int eye_side(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, const Eye& eye) {
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const Interval ux = Interval(q.x) - p.x, uy = Interval(q.y) - p.y, uz = Interval(q.z) - p.z;
    const Interval vx = Interval(s.x) - r.x, vy = Interval(s.y) - r.y, vz = Interval(s.z) - r.z;
    const Interval nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    auto h = [&](std::size_t j) { return Interval(eye.near[j][0], eye.near[j][1]); };
    const Interval d = nx * (h(0) - h(3) * p.x) + ny * (h(1) - h(3) * p.y) + nz * (h(2) - h(3) * p.z);
    if (d.inf() > 0) return 1;
    if (d.sup() < 0) return -1;
    if (d.inf() == 0 && d.sup() == 0) return 0;
  }
  const mpq_class ux = mpq_class(q.x) - p.x, uy = mpq_class(q.y) - p.y, uz = mpq_class(q.z) - p.z;
  const mpq_class vx = mpq_class(s.x) - r.x, vy = mpq_class(s.y) - r.y, vz = mpq_class(s.z) - r.z;
  const mpq_class nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  return sgn(nx * (eye.h[0] - eye.h[3] * p.x) + ny * (eye.h[1] - eye.h[3] * p.y) + nz * (eye.h[2] - eye.h[3] * p.z));
}

std::vector<std::uint32_t> back_to_front(const BspTree& t, const Scene& scene, const Eye& eye) {
  std::vector<std::uint32_t> order;
  order.reserve(t.fragments.size());
  if (t.root < 0) return order;
  // Nodes to visit, and nodes whose own fragments are due (negative entries: ~node).
  std::vector<int> stack{t.root};
  std::vector<std::uint32_t> on;
  while (!stack.empty()) {
    const int item = stack.back();
    stack.pop_back();
    if (item < 0) {
      // The fragments in the node's plane: at equal depth the lower face index
      // shows, so it is drawn later.
      on = t.nodes[static_cast<std::size_t>(~item)].on;
      std::sort(on.begin(), on.end(), [&](std::uint32_t x, std::uint32_t y) {
        const int fx = t.facets->facets[t.fragments[x].facet].face, fy = t.facets->facets[t.fragments[y].facet].face;
        return fx != fy ? fx > fy : x < y;
      });
      order.insert(order.end(), on.begin(), on.end());
      continue;
    }
    const BspTree::Node& node = t.nodes[static_cast<std::size_t>(item)];
    const Vec3 &o = scene.vertices[node.span[0]];
    const bool eye_in_front = eye_side(o, scene.vertices[node.span[1]], o, scene.vertices[node.span[2]], eye) >= 0;
    const int first = eye_in_front ? node.back : node.front, last = eye_in_front ? node.front : node.back;
    // (A stack: pushed in reverse.)
    if (last >= 0) stack.push_back(last);
    stack.push_back(~item);
    if (first >= 0) stack.push_back(first);
  }
  return order;
}

}  // namespace vismap::engine
