#include "verify/union_area.h"

#include <algorithm>

namespace vismap_check {
namespace {

struct Edge {
  P2 a, b;               // a.x < b.x
  std::size_t piece;
  mpq_class slope;
  mpq_class y_at(const mpq_class& x) const {
    mpq_class y = a.y + (x - a.x) * slope;
    return y;
  }
};

}  // namespace

mpq_class union_area(const Screen& sc) {
  std::vector<Edge> edges;
  std::vector<mpq_class> xs;
  for (std::size_t pi = 0; pi < sc.pieces.size(); ++pi) {
    const Piece& p = sc.pieces[pi];
    if (p.orient == 0) continue;
    for (std::size_t i = 0, n = p.xy.size(); i < n; ++i) {
      const P2& u = p.xy[i];
      const P2& v = p.xy[p.next(i)];
      xs.push_back(u.x);
      if (u.x == v.x) continue;   // vertical edges bound no slab
      Edge e{u.x < v.x ? u : v, u.x < v.x ? v : u, pi, 0};
      e.slope = (e.b.y - e.a.y) / (e.b.x - e.a.x);
      edges.push_back(std::move(e));
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& l, const Edge& r) { return l.a.x < r.a.x; });
  // Proper crossings; touching and overlaps happen at vertices, already in xs.
  // A crossing strictly inside some piece is not on the union's boundary, and
  // the covered set does not change shape there: it needs no slab.
  auto buried = [&](const P2& c) {
    for (std::uint32_t pi : sc.grid.near(c)) {
      const Piece& p = sc.pieces[pi];
      if (p.orient != 0 && p.box.contains(c) && locate(c, p) == Where::Inside) return true;
    }
    return false;
  };
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Edge& e = edges[i];
    const mpq_class ey0 = std::min(e.a.y, e.b.y), ey1 = std::max(e.a.y, e.b.y);
    for (std::size_t j = i + 1; j < edges.size() && edges[j].a.x < e.b.x; ++j) {
      const Edge& f = edges[j];
      if (std::max(f.a.y, f.b.y) < ey0 || std::min(f.a.y, f.b.y) > ey1) continue;
      int o1 = orient(e.a, e.b, f.a), o2 = orient(e.a, e.b, f.b);
      if (o1 * o2 >= 0) continue;
      int o3 = orient(f.a, f.b, e.a), o4 = orient(f.a, f.b, e.b);
      if (o3 * o4 >= 0) continue;
      mpq_class ca = cross(f.a, e.a, f.b), cb = cross(f.a, e.b, f.b);
      mpq_class t = ca / (ca - cb);
      P2 c{e.a.x + t * (e.b.x - e.a.x), e.a.y + t * (e.b.y - e.a.y)};
      if (!buried(c)) xs.push_back(std::move(c.x));
    }
  }
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());

  mpq_class total = 0;
  std::vector<std::size_t> active;          // kept in (y0, y1) order between slabs
  std::vector<mpq_class> y0(edges.size()), y1(edges.size());
  std::vector<char> parity(sc.pieces.size(), 0);
  std::size_t next = 0;
  for (std::size_t k = 0; k + 1 < xs.size(); ++k) {
    const mpq_class& x0 = xs[k];
    const mpq_class& x1 = xs[k + 1];
    std::erase_if(active, [&](std::size_t i) { return edges[i].b.x <= x0; });
    while (next < edges.size() && edges[next].a.x <= x0) {
      y0[next] = edges[next].a.y;
      active.push_back(next++);
    }
    for (std::size_t i : active) y1[i] = edges[i].y_at(x1);
    // The order just right of x0 (buried crossings may reorder edges inside a
    // slab, but only where the union is covered anyway). Insertion sort: the
    // order changes only at crossings, so it is nearly sorted.
    auto less = [&](std::size_t l, std::size_t r) {
      return y0[l] < y0[r] || (y0[l] == y0[r] && edges[l].slope < edges[r].slope);
    };
    for (std::size_t i = 1; i < active.size(); ++i) {
      std::size_t v = active[i], j = i;
      while (j > 0 && less(v, active[j - 1])) {
        active[j] = active[j - 1];
        --j;
      }
      active[j] = v;
    }
    // Sweep upwards: covered while some piece has odd parity.
    std::size_t odd = 0;
    mpq_class sum = 0, start;
    for (std::size_t i : active) {
      std::size_t p = edges[i].piece;
      parity[p] ^= 1;
      if (parity[p]) {
        if (odd++ == 0) start = y0[i] + y1[i];
      } else if (--odd == 0) {
        sum += y0[i] + y1[i] - start;
      }
    }
    total += sum * (x1 - x0) / 2;
    for (std::size_t i : active) y0[i] = y1[i];
  }
  return total;
}

}  // namespace vismap_check
