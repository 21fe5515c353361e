// Step 10 without a sweep: Franklin's pieces already meet only at their end
// points (every crossing, T-junction and overlap end was cut in step 8), so the
// plane graph is assembled directly. Equal end points are found by sorting (most
// are the very same point object, so no exact value is needed), edges are sorted
// around each vertex with filtered orientation tests, faces are traced, and each
// connected component is placed in the face below its lowest-leftmost vertex by
// one vertical ray. No segment intersection is ever computed.
#include <algorithm>
#include <atomic>
#include <climits>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "arrangements/map_graph.h"
#include "engine/parallel.h"

namespace vismap {
VISMAP_KERNEL_BEGIN
namespace {

using namespace exact;

[[noreturn]] void broken(const char* what) {
  throw std::logic_error(std::string("visibility map: ") + what + " (engine bug)");
}

const CGAL::Simple_cartesian<Interval>::Point_2& approx_point(const P2& p) { return p.approx(); }

// Vertices: the distinct end points, numbered in lexicographic order.
// A rational's GMP value, without a copy (CGAL's exact numbers are mpq_class or
// Boost's gmp_rational, by what is included).
inline mpq_srcptr raw(const mpq_class& q) { return q.get_mpq_t(); }
template <class Boost_rational>
mpq_srcptr raw(const Boost_rational& q) { return q.backend().data(); }

CGAL::Comparison_result as_comparison(int c) { return c < 0 ? CGAL::SMALLER : c > 0 ? CGAL::LARGER : CGAL::EQUAL; }

// compare_xy of two points whose x intervals overlap, on their exact values
// (computed once per point). Mostly their x are equal (seen along a rational
// direction, a grid's vertices fall in columns of one exact x: a 10^6-triangle
// terrain asked this 17 M times): canonical rationals are equal when their
// limbs are, and then y's intervals usually decide. No rounding-mode switch, no
// interval retried, as CGAL's filtered predicate would for every one of them.
using ExactPoint = std::remove_cvref_t<decltype(CGAL::exact(std::declval<const P2&>()))>;
CGAL::Comparison_result exact_compare_xy(const ExactPoint& ea, const ExactPoint& eb, const Interval& ay,
                                         const Interval& by) {
  if (!mpq_equal(raw(ea.x()), raw(eb.x()))) return as_comparison(mpq_cmp(raw(ea.x()), raw(eb.x())));
  if (ay.sup() < by.inf()) return CGAL::SMALLER;
  if (by.sup() < ay.inf()) return CGAL::LARGER;
  return as_comparison(mpq_cmp(raw(ea.y()), raw(eb.y())));
}

// Each piece end's stand-in (2 * piece + 0 for its a, + 1 for its b): among
// the ends with one name (MapPiece::ida, idb), the first in piece order; an
// unnamed end stands for itself. (The first of each name found side by side on
// the threads: the least of its ends, whichever thread sees it.)
std::vector<int> stand_ins(const std::vector<MapPiece>& pieces, int threads) {
  const int nends = 2 * static_cast<int>(pieces.size()), size = 16384;
  auto name = [&](int at) { return at % 2 == 0 ? pieces[at / 2].ida : pieces[at / 2].idb; };
  std::vector<int> most(static_cast<std::size_t>(engine::chunk_count(nends, size)), -1);
  engine::parallel_chunks(nends, size, threads, [&](int c, engine::Chunk r) {
    int m = -1;   // (stored once)
    for (int at = r.begin; at < r.end; ++at) m = std::max(m, name(at));
    most[static_cast<std::size_t>(c)] = m;
  });
  int names = 0;
  for (const int m : most) names = std::max(names, m + 1);
  std::vector<int> first(static_cast<std::size_t>(names), INT_MAX);
  engine::parallel_chunks(nends, size, threads, [&](int, engine::Chunk r) {
    for (int at = r.begin; at < r.end; ++at)
      if (const int id = name(at); id >= 0) {
        std::atomic_ref<int> f(first[static_cast<std::size_t>(id)]);
        int seen = f.load(std::memory_order_relaxed);
        while (at < seen && !f.compare_exchange_weak(seen, at, std::memory_order_relaxed)) {
        }
      }
  });
  std::vector<int> stand_in(static_cast<std::size_t>(nends));
  engine::parallel_chunks(nends, size, threads, [&](int, engine::Chunk r) {
    for (int at = r.begin; at < r.end; ++at) {
      const int id = name(at);
      stand_in[static_cast<std::size_t>(at)] = id >= 0 ? first[static_cast<std::size_t>(id)] : at;
    }
  });
  return stand_in;
}

std::vector<int> number_end_points(const std::vector<MapPiece>& pieces, MapGraph& g, int threads) {
  struct End {   // (24 bytes: one per point named once, or per unnamed end)
    Interval x;   // sorts most pairs without touching the point
    int at;       // 2 * piece + (0: a, 1: b)
  };
  auto end_point = [&](int at) -> const P2& { return at % 2 == 0 ? pieces[at / 2].a : pieces[at / 2].b; };
  auto point = [&](const End& e) -> const P2& { return end_point(e.at); };
  const int npieces = static_cast<int>(pieces.size());
  // Ends named by the engine (MapPiece::ida, idb) are sorted once per name: the
  // first end with each, in piece order, stands for the others (a 10^6-triangle
  // terrain's 3 M ends are 0.5 M vertices). Each end's stand-in, and the ends
  // that are sorted: the stand-ins and the unnamed ends, in piece order.
  const std::vector<int> stand_in = stand_ins(pieces, threads);
  std::vector<End> ends;
  {
    const int nends = 2 * npieces, size = 16384;
    ends.reserve(static_cast<std::size_t>(nends));
    engine::parallel_append(ends, engine::chunk_count(nends, size), threads, [&](int c, std::vector<End>& out) {
      const engine::Chunk r = engine::chunk(c, nends, size);
      for (int at = r.begin; at < r.end; ++at)
        if (stand_in[at] == at) out.push_back(End{approx_point(end_point(at)).x(), at});
    });
  }
  // A cheap number equal to end e's x, where the engine knows one (MapPiece::xa:
  // a vertex's x, or the x of the upright screen line its piece lies on), or
  // null. Two ends with one such number (of one vertical edge, seen with the up
  // axis vertical) are then ordered by y alone, mostly by y's intervals, with no
  // exact value made.
  auto known_x = [&](const End& e) { return e.at % 2 == 0 ? pieces[e.at / 2].xa : pieces[e.at / 2].xb; };
  // (pa, pb: the two ends' points; exact_a(), exact_b(): their exact values,
  // wherever they are kept.)
  auto compare_with = [&](const End& a, const P2& pa, const End& b, const P2& pb, auto&& exact_a, auto&& exact_b) {
    if (a.x.sup() < b.x.inf()) return CGAL::SMALLER;
    if (b.x.sup() < a.x.inf()) return CGAL::LARGER;
    if (exact::same_rep(pa, pb)) return CGAL::EQUAL;
    const Interval &ay = approx_point(pa).y(), &by = approx_point(pb).y();
    bool x_equal = a.x.is_point() && b.x.is_point();
    if (!x_equal) {   // x known as cheap numbers: those compare instead of the points
      const FT *xa = known_x(a), *xb = known_x(b);
      if (xa && xb) {
        const CGAL::Comparison_result c = CGAL::identical(*xa, *xb) ? CGAL::EQUAL : compare_uncounted(*xa, *xb);
        if (c != CGAL::EQUAL) return c;
        x_equal = true;
      }
    }
    if (x_equal) {   // x equal: y's intervals may tell
      if (ay.sup() < by.inf()) return CGAL::SMALLER;
      if (by.sup() < ay.inf()) return CGAL::LARGER;
    }
    return exact_compare_xy(exact_a(), exact_b(), ay, by);
  };
  auto compare = [&](const End& a, const End& b) {
    const P2 &pa = point(a), &pb = point(b);
    return compare_with(a, pa, b, pb, [&]() -> const ExactPoint& { return CGAL::exact(pa); },
                        [&]() -> const ExactPoint& { return CGAL::exact(pb); });
  };
  // Equal points in the order of their pieces: the same order for every thread
  // count. How many comparisons a parallel sort makes depends on the thread count,
  // so its predicates are not counted (the stats must not depend on it either).
  // Sorted in two steps, which give the one order: by x's lower bound (doubles),
  // which puts ends whose x intervals are apart in order; then each run of ends
  // whose intervals overlap one another in a chain (points of one exact x, on a
  // mesh seen along a rational direction: a terrain's columns) by `compare`,
  // the runs side by side on the threads.
  const FilterCounts before_sort = filter_counts;
  engine::parallel_sort(ends.begin(), ends.end(), [](const End& a, const End& b) {
    return a.x.inf() < b.x.inf() || (a.x.inf() == b.x.inf() && a.at < b.at);
  }, threads);
  std::vector<engine::Chunk> runs;   // (of two ends or more)
  for (std::size_t k = 0; k < ends.size();) {
    std::size_t last = k;
    for (double reach = ends[k].x.sup(); last + 1 < ends.size() && !(reach < ends[last + 1].x.inf());)
      reach = std::max(reach, ends[++last].x.sup());
    if (last > k) runs.push_back({static_cast<int>(k), static_cast<int>(last + 1)});
    k = last + 1;
  }
  // Where a new point starts among the sorted ends: 1 or 0, found with a run's
  // sort (its ends but the first), else 2 (found below).
  std::vector<char> starts(ends.size(), 2);
  engine::parallel_chunks(static_cast<int>(runs.size()), 64, threads, [&](int, engine::Chunk r) {
    // (Each end kept beside its point, and its exact point once found, at its
    // first exact comparison: a terrain's columns make millions of them.)
    struct Kept {
      End end;
      const P2* p;
      mutable const ExactPoint* exact = nullptr;
      const ExactPoint& exact_point() const { return exact ? *exact : *(exact = &CGAL::exact(*p)); }
    };
    auto compare_kept = [&](const Kept& a, const Kept& b) {
      return compare_with(a.end, *a.p, b.end, *b.p, [&]() -> const ExactPoint& { return a.exact_point(); },
                          [&]() -> const ExactPoint& { return b.exact_point(); });
    };
    std::vector<Kept> run;
    for (int i = r.begin; i < r.end; ++i) {
      const auto first = ends.begin() + runs[i].begin, last = ends.begin() + runs[i].end;
      run.clear();
      for (auto e = first; e != last; ++e) run.push_back(Kept{*e, &point(*e)});
      std::sort(run.begin(), run.end(), [&](const Kept& a, const Kept& b) {
        const CGAL::Comparison_result c = compare_kept(a, b);
        return c == CGAL::SMALLER || (c == CGAL::EQUAL && a.end.at < b.end.at);
      });
      for (std::size_t k = 0; k < run.size(); ++k) {
        first[static_cast<std::ptrdiff_t>(k)] = run[k].end;
        const std::size_t at = static_cast<std::size_t>(runs[i].begin) + k;
        if (k > 0) starts[at] = compare_kept(run[k - 1], run[k]) != CGAL::EQUAL;
      }
    }
  });
  filter_counts = before_sort;
  // Chunks of the sorted ends in parallel: where a new point starts, how many
  // each chunk has; then each chunk's points, numbered from its first.
  const int n = static_cast<int>(ends.size()), size = 16384, chunks = engine::chunk_count(n, size);
  std::vector<int> first(static_cast<std::size_t>(chunks) + 1, 0);
  engine::parallel_chunks(n, size, threads, [&](int c, engine::Chunk r) {
    int count = 0;
    for (int k = r.begin; k < r.end; ++k) {
      if (starts[k] == 2) starts[k] = k == 0 || compare(ends[k - 1], ends[k]) != CGAL::EQUAL;
      count += starts[k];
    }
    first[c + 1] = count;
  });
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<int> vertex_of(stand_in.size());
  g.points.reserve(static_cast<std::size_t>(first.back()));
  engine::parallel_append(g.points, chunks, threads, [&](int c, std::vector<P2>& points) {
    const engine::Chunk r = engine::chunk(c, n, size);
    int w = first[c] - 1;
    for (int k = r.begin; k < r.end; ++k) {
      if (starts[k]) {
        points.push_back(point(ends[k]));
        ++w;
      }
      vertex_of[ends[k].at] = w;
    }
  });
  engine::parallel_chunks(static_cast<int>(stand_in.size()), 16384, threads, [&](int, engine::Chunk r) {
    for (int at = r.begin; at < r.end; ++at)
      if (stand_in[at] != at) vertex_of[at] = vertex_of[stand_in[at]];   // (a stand-in's own is set)
  });
  g.approx.resize(g.points.size());
  engine::parallel_chunks(static_cast<int>(g.points.size()), 16384, threads, [&](int, engine::Chunk r) {
    for (int w = r.begin; w < r.end; ++w) {
      const auto k = static_cast<std::size_t>(w);
      g.approx[k] = g.points[k].approx();
    }
  });
  return vertex_of;
}

// sign(y of edge 1 - y of edge 2) at x, both edges spanning x (u.x < x < v.x).
CGAL::Sign compare_y_at(const P2& x, const P2& u1, const P2& v1, const P2& u2, const P2& v2) {
  return filtered_sign(
      [&] {
        const auto &X = approx_point(x), &U1 = approx_point(u1), &V1 = approx_point(v1), &U2 = approx_point(u2),
                   &V2 = approx_point(v2);
        const Interval d1 = V1.x() - U1.x(), d2 = V2.x() - U2.x();
        const Interval n1 = U1.y() * d1 + (X.x() - U1.x()) * (V1.y() - U1.y());
        const Interval n2 = U2.y() * d2 + (X.x() - U2.x()) * (V2.y() - U2.y());
        return n1 * d2 - n2 * d1;
      },
      [&]() -> mpq_class {
        const auto &X = CGAL::exact(x), &U1 = CGAL::exact(u1), &V1 = CGAL::exact(v1), &U2 = CGAL::exact(u2),
                   &V2 = CGAL::exact(v2);
        const mpq_class d1 = to_mpq(V1.x()) - to_mpq(U1.x()), d2 = to_mpq(V2.x()) - to_mpq(U2.x());
        const mpq_class n1 = to_mpq(U1.y()) * d1 + (to_mpq(X.x()) - to_mpq(U1.x())) * (to_mpq(V1.y()) - to_mpq(U1.y()));
        const mpq_class n2 = to_mpq(U2.y()) * d2 + (to_mpq(X.x()) - to_mpq(U2.x())) * (to_mpq(V2.y()) - to_mpq(U2.y()));
        return n1 * d2 - n2 * d1;
      });
}

struct Assembly {
  Assembly(MapGraph& graph, int thread_count) : g(graph), threads(thread_count) {}
  MapGraph& g;
  int threads = 1;
  int nverts = 0, nhalf = 0;
  std::vector<int> first;      // vertex -> its outgoing halfedges rot[first[w] .. first[w+1])
  std::vector<int> rot;        // counter-clockwise from angle 0 (the +x direction)
  std::vector<int> pos;        // halfedge -> its index in rot
  std::vector<char> upper;     // halfedge -> direction in [0, pi): dy > 0, or dy = 0 and dx > 0
  std::vector<int> cycle;      // halfedge -> boundary cycle
  std::vector<char> positive;  // cycle -> counter-clockwise (the outer boundary of a bounded face)

  int source(int h) const { return g.ends[h >> 1][h & 1]; }
  int target(int h) const { return g.ends[h >> 1][(h & 1) ^ 1]; }
  const P2& at(int w) const { return g.points[w]; }

  // CGAL::orientation of vertices u, v, w: on their intervals where those tell
  // (the caller holds UpwardRounding), else exactly.
  CGAL::Orientation turn(int u, int v, int w) const {
    return filtered_sign(
        [&] {
          const auto &p = g.approx[u], &q = g.approx[v], &r = g.approx[w];
          return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
        },
        [&] {
          const CGAL::Orientation o = CGAL::orientation(CGAL::exact(at(u)), CGAL::exact(at(v)), CGAL::exact(at(w)));
          return mpq_class(static_cast<int>(o));
        });
  }

  // Edges around each vertex, counter-clockwise; then each halfedge's next.
  void sort_around_vertices() {
    nverts = static_cast<int>(g.points.size());
    nhalf = static_cast<int>(2 * g.ends.size());
    first.assign(nverts + 1, 0);
    for (int h = 0; h < nhalf; ++h) ++first[source(h) + 1];
    std::partial_sum(first.begin(), first.end(), first.begin());
    rot.resize(nhalf);
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (int h = 0; h < nhalf; ++h) rot[fill[source(h)]++] = h;
    upper.resize(nhalf);
    // (An edge's two halfedges point opposite ways: one each. Compared on the
    // points' bounds, without CGAL's rounding switch at every call.)
    engine::parallel_chunks(nhalf / 2, 8192, threads, [&](int, engine::Chunk r) {
      for (int e = r.begin; e < r.end; ++e) {
        const int h = 2 * e;
        const CGAL::Comparison_result dy = compare_coordinate_exactly(at(target(h)), at(source(h)), false);
        upper[h] = dy == CGAL::LARGER || (dy == CGAL::EQUAL && target(h) > source(h));
        upper[h + 1] = !upper[h];
      }
    });
    // Each vertex's edges, and their places around it: chunks of vertices in parallel.
    pos.resize(nhalf);
    engine::parallel_chunks(nverts, 4096, threads, [&](int, engine::Chunk r) {
      UpwardRounding upward;   // (turn's intervals: one rounding switch per chunk)
      for (int w = r.begin; w < r.end; ++w) {
        auto before = [&](int h1, int h2) {
          if (upper[h1] != upper[h2]) return upper[h1] > upper[h2];
          const CGAL::Orientation o = turn(w, target(h1), target(h2));
          if (o == CGAL::COLLINEAR && h1 != h2) broken("overlapping pieces with different end points");
          return o == CGAL::LEFT_TURN;
        };
        std::sort(rot.begin() + first[w], rot.begin() + first[w + 1], before);
        for (int k = first[w]; k < first[w + 1]; ++k) pos[rot[k]] = k - first[w];
      }
    });
    // Face on the left: arriving at w along h, leave along the edge just
    // clockwise of the way back.
    g.next.resize(nhalf);
    engine::parallel_chunks(nhalf, 16384, threads, [&](int, engine::Chunk r) {
      for (int h = r.begin; h < r.end; ++h) {
        const int w = target(h), deg = first[w + 1] - first[w], back = pos[h ^ 1];
        g.next[h] = rot[first[w] + (back == 0 ? deg - 1 : back - 1)];
      }
    });
  }

  // Boundary cycles, and which are counter-clockwise (signed area > 0: on
  // intervals, exactly where they cannot tell).
  void trace_cycles() {
    // The cycles numbered in order of their first halfedge (a walk along next:
    // cheap), then their signed areas, the costly part, in parallel.
    cycle.assign(nhalf, -1);
    std::vector<int> start;   // cycle -> its first halfedge
    for (int h0 = 0; h0 < nhalf; ++h0) {
      if (cycle[h0] >= 0) continue;
      const int c = static_cast<int>(start.size());
      start.push_back(h0);
      int h = h0;
      do {
        cycle[h] = c;
        h = g.next[h];
      } while (h != h0);
    }
    positive.assign(start.size(), 0);
    engine::parallel_chunks(static_cast<int>(start.size()), 1024, threads, [&](int, engine::Chunk r) {
      for (int c = r.begin; c < r.end; ++c) positive[static_cast<std::size_t>(c)] = counter_clockwise(start[c]);
    });
  }

  // Whether the cycle through h0 turns counter-clockwise: the sign of its
  // area, on intervals, exactly where they cannot tell.
  bool counter_clockwise(int h0) const {
    Interval area = 0;
    {
      CGAL::Protect_FPU_rounding<true> upward;
      int h = h0;
      do {
        const auto &p = g.approx[source(h)], &q = g.approx[target(h)];
        area += p.x() * q.y() - q.x() * p.y();
        h = g.next[h];
      } while (h != h0);
    }
    if (area.inf() > 0 || area.sup() <= 0) return area.inf() > 0;
    ++filter_counts.exact;
    mpq_class s = 0;
    int h = h0;
    do {
      const auto &p = CGAL::exact(at(source(h))), &q = CGAL::exact(at(target(h)));
      s += to_mpq(p.x()) * to_mpq(q.y()) - to_mpq(q.x()) * to_mpq(p.y());
      h = g.next[h];
    } while (h != h0);
    return sgn(s) > 0;
  }

  // The outgoing halfedge at w whose face holds the directions just
  // counter-clockwise of it up to `dir` (the last one before `dir`, cyclically).
  // dir: +y (up) or -x (left).
  int halfedge_before(int w, bool up) const {
    int found = rot[first[w + 1] - 1];
    for (int k = first[w]; k < first[w + 1]; ++k) {
      const int h = rot[k];
      if (!upper[h]) break;
      if (up && CGAL::compare_x(at(target(h)), at(w)) != CGAL::LARGER) break;
      found = h;
    }
    return found;
  }
};

// Vertical ray shooting: edges by columns of x (doubles), each edge in every
// column its x-range meets. About sqrt(E) columns; fewer where long edges would
// make the lists longer than 8 entries per edge (memory stays linear).
struct Columns {
  double x0 = 0, width = 1;
  int n = 1;
  engine::Buckets edges;   // each column's edges, in edge order

  int column(double x) const { return std::clamp(static_cast<int>(std::floor((x - x0) / width)), 0, n - 1); }

  // (The bounds and the totals in parts on `threads` threads, then added.)
  Columns(const MapGraph& g, int threads) {
    const int E = static_cast<int>(g.ends.size()), nv = static_cast<int>(g.approx.size()), size = 16384;
    std::vector<std::array<double, 2>> bounds(static_cast<std::size_t>(engine::chunk_count(nv, size)));
    engine::parallel_chunks(nv, size, threads, [&](int k, engine::Chunk r) {
      double lo = HUGE_VAL, hi = -HUGE_VAL;   // (stored once)
      for (int w = r.begin; w < r.end; ++w) {
        lo = std::min(lo, g.approx[static_cast<std::size_t>(w)].x().inf());
        hi = std::max(hi, g.approx[static_cast<std::size_t>(w)].x().sup());
      }
      bounds[static_cast<std::size_t>(k)] = {lo, hi};
    });
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (const auto& b : bounds) {
      lo = std::min(lo, b[0]);
      hi = std::max(hi, b[1]);
    }
    x0 = lo;
    auto each_column = [&](int e, auto&& visit) {
      const int c0 = column(g.approx[g.ends[e][0]].x().inf()), c1 = column(g.approx[g.ends[e][1]].x().sup());
      for (int c = c0; c <= c1; ++c) visit(static_cast<std::size_t>(c));
    };
    std::vector<std::size_t> totals(static_cast<std::size_t>(engine::chunk_count(E, size)));
    for (n = static_cast<int>(std::clamp(std::sqrt(static_cast<double>(E)), 1.0, 65536.0));; n = std::max(1, n / 4)) {
      width = hi > lo ? (hi - lo) / n : 1;
      engine::parallel_chunks(E, size, threads, [&](int k, engine::Chunk r) {
        std::size_t total = 0;
        for (int e = r.begin; e < r.end; ++e) each_column(e, [&](std::size_t) { ++total; });
        totals[static_cast<std::size_t>(k)] = total;
      });
      const std::size_t total = std::accumulate(totals.begin(), totals.end(), std::size_t{0});
      if (n == 1 || total <= 8 * static_cast<std::size_t>(E)) break;
    }
    edges = engine::bucket_items(E, static_cast<std::size_t>(n), threads, each_column);
  }
};

// The halfedge whose face lies directly below w (-1: the unbounded face), w being
// the lowest-leftmost vertex of its component (so no edge of its own is below it).
int face_below(const Assembly& a, const Columns& cols, int w) {
  const MapGraph& g = a.g;
  const P2& p = g.points[w];
  const Interval px = g.approx[w].x();
  int best_vertex = -1, best_edge = -1;
  // Is vertex q above the best hit so far?
  auto vertex_higher = [&](int q) {
    if (best_vertex >= 0) return CGAL::compare_y(g.points[q], g.points[best_vertex]) == CGAL::LARGER;
    if (best_edge >= 0) {
      const auto o = CGAL::orientation(g.points[g.ends[best_edge][0]], g.points[g.ends[best_edge][1]], g.points[q]);
      if (o == CGAL::COLLINEAR) broken("a vertex inside an edge");
      return o == CGAL::LEFT_TURN;
    }
    return true;
  };
  auto edge_higher = [&](int e) {
    const P2 &u = g.points[g.ends[e][0]], &v = g.points[g.ends[e][1]];
    if (best_vertex >= 0) {
      const auto o = CGAL::orientation(u, v, g.points[best_vertex]);
      if (o == CGAL::COLLINEAR) broken("a vertex inside an edge");
      return o == CGAL::RIGHT_TURN;
    }
    if (best_edge >= 0) {
      const P2 &u2 = g.points[g.ends[best_edge][0]], &v2 = g.points[g.ends[best_edge][1]];
      const CGAL::Sign s = compare_y_at(p, u, v, u2, v2);
      if (s == CGAL::ZERO) broken("crossing pieces");
      return s == CGAL::POSITIVE;
    }
    return true;
  };
  const int c0 = cols.column(px.inf()), c1 = cols.column(px.sup());
  for (int c = c0; c <= c1; ++c)
    for (std::uint32_t k = cols.edges.first[c]; k < cols.edges.first[c + 1]; ++k) {
      const int e = static_cast<int>(cols.edges.items[k]);
      if (e == best_edge) continue;   // listed in both columns
      const int iu = g.ends[e][0], iv = g.ends[e][1];
      const P2 &u = g.points[iu], &v = g.points[iv];
      if (g.approx[iu].x().inf() > px.sup() || g.approx[iv].x().sup() < px.inf()) continue;
      const auto cu = CGAL::compare_x(u, p), cv = CGAL::compare_x(v, p);
      if (cu == CGAL::LARGER || cv == CGAL::SMALLER) continue;
      int q = -1;   // the hit is a vertex (the edge's highest point at p.x)
      if (cv == CGAL::EQUAL) q = iv;
      else if (cu == CGAL::EQUAL) q = iu;
      if (q >= 0) {
        if (CGAL::compare_y(g.points[q], p) == CGAL::SMALLER && vertex_higher(q)) { best_vertex = q; best_edge = -1; }
        continue;
      }
      const auto o = CGAL::orientation(u, v, p);
      if (o == CGAL::COLLINEAR) broken("a vertex inside an edge");
      if (o == CGAL::LEFT_TURN && edge_higher(e)) { best_edge = e; best_vertex = -1; }
    }
  if (best_vertex >= 0) return a.halfedge_before(best_vertex, true);
  if (best_edge >= 0) return 2 * best_edge;   // left to right: the face above is on its left
  return -1;
}

// Edges: pieces from the smaller end, those on the same two vertices merged.
void add_edges(std::vector<MapPiece>& pieces, MapGraph& g, int threads) {
  std::vector<int> vertex_of = number_end_points(pieces, g, threads);
  const int n = static_cast<int>(pieces.size()), size = 16384;
  engine::parallel_chunks(n, size, threads, [&](int, engine::Chunk r) {
    for (int i = r.begin; i < r.end; ++i) {
      MapPiece& m = pieces[i];
      int &u = vertex_of[2 * i], &v = vertex_of[2 * i + 1];
      if (u == v) broken("a piece of length zero");
      if (v < u) { std::swap(m.a, m.b); std::swap(m.left, m.right); std::swap(u, v); }
    }
  });
  auto key = [&](int i) { return std::pair(vertex_of[2 * i], vertex_of[2 * i + 1]); };
  // The pieces in order of (key, piece): by u in a counting sort (vertices are
  // numbers; each lists its pieces in piece order), then each vertex's few by v.
  // (A comparison sort of 10^6 pieces read both keys at random.)
  const engine::Buckets by_u = engine::bucket_items(n, g.points.size(), threads, [&](int i, auto&& in) {
    in(static_cast<std::size_t>(vertex_of[2 * static_cast<std::size_t>(i)]));
  });
  std::vector<int> order(by_u.items.begin(), by_u.items.end());
  engine::parallel_chunks(static_cast<int>(g.points.size()), 4096, threads, [&](int, engine::Chunk r) {
    auto before = [&](int i, int j) { return std::pair(key(i), i) < std::pair(key(j), j); };
    for (int u = r.begin; u < r.end; ++u) {
      const auto b = order.begin() + by_u.first[static_cast<std::size_t>(u)];
      const auto e = order.begin() + by_u.first[static_cast<std::size_t>(u) + 1];
      if (e - b <= 16) {   // (insertion: most vertices have a handful)
        for (auto i = b; i != e; ++i)
          for (auto j = i; j != b && before(*j, *(j - 1)); --j) std::iter_swap(j, j - 1);
      } else {
        std::sort(b, e, before);
      }
    }
  });
  // One edge per run of equal keys: where the runs start (chunks of the order
  // side by side, appended in order), then each edge (in chunks).
  std::vector<int> starts;
  engine::parallel_append(starts, engine::chunk_count(n, size), threads, [&](int c, std::vector<int>& out) {
    const engine::Chunk r = engine::chunk(c, n, size);
    for (int k = r.begin; k < r.end; ++k)
      if (k == 0 || key(order[k]) != key(order[k - 1])) out.push_back(k);
  });
  starts.push_back(n);
  const int nedges = static_cast<int>(starts.size()) - 1;
  g.ends.resize(static_cast<std::size_t>(nedges));
  g.attrs.resize(static_cast<std::size_t>(nedges));
  engine::parallel_chunks(nedges, 4096, threads, [&](int, engine::Chunk r) {
    for (int e = r.begin; e < r.end; ++e) {
      const int k = starts[e], l = starts[e + 1];
      const auto [u, v] = key(order[k]);
      g.ends[e] = {u, v};
      g.attrs[e] = edge_attr(pieces, &order[k], static_cast<std::size_t>(l - k), g.points[u], g.points[v]);
    }
  });
}

}  // namespace

MapGraph graph_of_pieces(std::vector<MapPiece>& pieces, int threads) {
  MapGraph g;
  add_edges(pieces, g, threads);
  return g;
}

void assemble_segments(std::vector<MapPiece>& pieces, VisibilityMap& map, int threads) {
  write_segments_only(graph_of_pieces(pieces, threads), map, threads);
}

void assemble_map(std::vector<MapPiece>& pieces, VisibilityMap& map, int threads) {
  MapGraph g = graph_of_pieces(pieces, threads);
  finish_map(g, map, threads);
}

namespace {

// The faces of the graph: each halfedge's next (g.next) and face (g.face, the
// unbounded one g.unbounded). The assembly's own arrays (five per halfedge)
// are freed on return, before the map is written: the peak (10^6 faces: ~90 MB).
void trace_faces(MapGraph& g, int threads) {
  Assembly a(g, threads);
  a.sort_around_vertices();
  a.trace_cycles();

  // Components, each with its lowest-leftmost vertex (the smallest number) and
  // its outer cycle: the one whose face holds the directions to the left there.
  // (Joined on the threads: each component's root is then its least vertex.)
  ConcurrentUnionFind comp(g.points.size());
  const int nedges = static_cast<int>(g.ends.size());
  engine::parallel_chunks(nedges, 16384, threads, [&](int, engine::Chunk r) {
    for (int e = r.begin; e < r.end; ++e) {
      const auto& [u, v] = g.ends[static_cast<std::size_t>(e)];
      comp.join(u, v);
    }
  });
  const std::vector<int> lowest = engine::indices_where(a.nverts, threads, [&](int w) { return comp.find(w) == w; });
  std::vector<int> outer_cycles(lowest.size());   // per component, in order of their lowest vertex
  engine::parallel_chunks(static_cast<int>(lowest.size()), 16384, threads, [&](int, engine::Chunk r) {
    for (int k = r.begin; k < r.end; ++k) {
      const int c = a.cycle[a.halfedge_before(lowest[static_cast<std::size_t>(k)], false)];
      if (a.positive[c]) broken("a component whose outside turns counter-clockwise");
      outer_cycles[static_cast<std::size_t>(k)] = c;
    }
  });
  const std::size_t ncycles = a.positive.size();
  const std::size_t npositive = static_cast<std::size_t>(std::count(a.positive.begin(), a.positive.end(), 1));
  if (ncycles - npositive != outer_cycles.size()) broken("pieces crossing between their end points");

  // Faces: one per counter-clockwise cycle, plus the unbounded one; each
  // component's outer cycle lies in the face below its lowest vertex. (That face
  // is found on a component whose lowest vertex comes earlier, so in this order
  // it is known.)
  std::vector<int> face_of(ncycles, -1);
  for (std::size_t c = 0; c < ncycles; ++c)
    if (a.positive[c]) face_of[c] = g.faces++;
  g.unbounded = g.faces++;
  if (!outer_cycles.empty()) {
    const Columns cols(g, threads);
    const int ncomp = static_cast<int>(outer_cycles.size());
    std::vector<int> below(outer_cycles.size());   // the rays in parallel, the faces in order
    engine::parallel_chunks(ncomp, 256, threads, [&](int, engine::Chunk r) {
      for (int k = r.begin; k < r.end; ++k) below[k] = face_below(a, cols, lowest[k]);
    });
    for (std::size_t k = 0; k < outer_cycles.size(); ++k) {
      const int h = below[k];
      const int f = h < 0 ? g.unbounded : face_of[a.cycle[h]];
      if (f < 0) broken("a face found out of order");
      face_of[outer_cycles[k]] = f;
    }
  }
  g.face.resize(a.nhalf);
  engine::parallel_chunks(a.nhalf, 16384, threads, [&](int, engine::Chunk r) {
    for (int h = r.begin; h < r.end; ++h) g.face[h] = face_of[a.cycle[h]];
  });
}

}  // namespace

void finish_map(MapGraph& g, VisibilityMap& map, int threads) {
  trace_faces(g, threads);
  write_canonical(g, map, threads);
}

VISMAP_KERNEL_END
}  // namespace vismap
