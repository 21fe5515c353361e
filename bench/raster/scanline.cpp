// The scan-line algorithm (Wylie et al., Bouknight, Watkins) as the lecture notes
// describe it: an edge table bucketed by first scan line, an active edge list kept
// sorted by x from one line to the next (insertion sort: the order barely
// changes), and an IN flag per piece that goes up and down as the beam crosses
// its edges. Between two consecutive crossings the set of pieces that are IN is
// constant: with none the span is background, with one it is that piece, and
// with several the depths are compared at the span's two end pixels; planes are
// linear, so when the same piece is nearest at both ends it is nearest across
// the whole span (for the order (depth, face) too). Only when the winners differ
// (pieces that interpenetrate inside the span) is the span resolved pixel by
// pixel.
//
// A non-horizontal edge is active on the rows whose centre y satisfies
// ymin <= y < ymax, so every row through a convex piece meets exactly two of
// its edges; a pixel centre lies in the span [x_k, x_k+1) of the crossings
// around it.
#include <algorithm>
#include <cmath>
#include <limits>

#include "bench/raster/raster.h"

namespace vismap::raster {
namespace {

struct Edge {
  double xb, yb, slope;   // x(y) = xb + (y - yb) * slope
  int piece;
  int last_row;
  double x;               // on the current row
};

}  // namespace

Image scanline(const ScreenScene& s, const Window& w) {
  const int R = w.R;
  Image img{R, std::vector<std::int32_t>(static_cast<std::size_t>(R) * R, -1)};
  const double inv = 1 / w.pixel;

  // Rows whose centre lies in [lo, hi): [first_row(lo), first_row(hi) - 1].
  auto first_row = [&](double yv) {   // first j with cy(j) >= yv, in [0, R]
    const double t = std::ceil((yv - w.y0) * inv - 0.5);
    int j = t <= 0 ? 0 : t >= R ? R : static_cast<int>(t);
    while (j < R && w.cy(j) < yv) ++j;
    while (j > 0 && w.cy(j - 1) >= yv) --j;
    return j;
  };

  // The edge table: non-horizontal edges bucketed by their first row.
  std::vector<std::vector<Edge>> table(static_cast<std::size_t>(R));
  for (std::size_t pi = 0; pi < s.pieces.size(); ++pi) {
    const Piece& p = s.pieces[pi];
    for (std::uint32_t k = 0; k < p.count; ++k) {
      const std::uint32_t a = p.first + k, b = p.first + (k + 1) % p.count;
      if (s.y[a] == s.y[b]) continue;
      const std::uint32_t lo = s.y[a] < s.y[b] ? a : b, hi = lo == a ? b : a;
      const int j0 = first_row(s.y[lo]), j1 = first_row(s.y[hi]) - 1;
      if (j0 > j1) continue;
      table[static_cast<std::size_t>(j0)].push_back(
          {s.x[lo], s.y[lo], (s.x[hi] - s.x[lo]) / (s.y[hi] - s.y[lo]), static_cast<int>(pi), j1, 0});
    }
  }

  std::vector<Edge> ael;                          // active edge list, sorted by x
  // The pieces whose IN flag is up, with their depth along the current row
  // (depth = a * x + row, row = b * y + c: Piece::depth, bitwise).
  struct In {
    int piece, face;
    double a, row;
  };
  std::vector<In> in;
  std::vector<int> slot(s.pieces.size(), -1);     // position in `in`, or -1
  double y = 0;                                   // the current row's centre
  auto toggle = [&](int pi) {
    if (slot[pi] < 0) {
      const Piece& p = s.pieces[pi];
      slot[pi] = static_cast<int>(in.size());
      in.push_back({pi, p.face, p.a, p.b * y + p.c});
    } else {
      const int at = slot[pi];
      in[at] = in.back();
      slot[in[at].piece] = at;
      in.pop_back();
      slot[pi] = -1;
    }
  };
  // The nearest IN piece at x on the current row, in the order (depth, face):
  // its position in `in`.
  auto nearest = [&](double x) {
    std::size_t best = 0;
    double bd = in[0].a * x + in[0].row;
    for (std::size_t k = 1; k < in.size(); ++k) {
      const double d = in[k].a * x + in[k].row;
      if (d < bd || (d == bd && in[k].face < in[best].face)) {
        best = k;
        bd = d;
      }
    }
    return best;
  };

  for (int j = 0; j < R; ++j) {
    y = w.cy(j);
    // Update the active edge list: drop finished edges, add new ones, move to y.
    std::size_t kept = 0;
    for (std::size_t k = 0; k < ael.size(); ++k)
      if (ael[k].last_row >= j) ael[kept++] = ael[k];
    ael.resize(kept);
    for (Edge& e : ael) e.x = e.xb + (y - e.yb) * e.slope;
    for (std::size_t k = 1; k < ael.size(); ++k) {   // insertion sort: crossings move little
      Edge e = ael[k];
      std::size_t m = k;
      while (m > 0 && ael[m - 1].x > e.x) {
        ael[m] = ael[m - 1];
        --m;
      }
      ael[m] = e;
    }
    // The edges starting on this row, sorted, merged in.
    auto& fresh = table[static_cast<std::size_t>(j)];
    for (Edge& e : fresh) e.x = e.xb + (y - e.yb) * e.slope;
    auto by_x = [](const Edge& a, const Edge& b) { return a.x < b.x; };
    std::sort(fresh.begin(), fresh.end(), by_x);
    const auto mid = static_cast<std::ptrdiff_t>(ael.size());
    ael.insert(ael.end(), fresh.begin(), fresh.end());
    std::inplace_merge(ael.begin(), ael.begin() + mid, ael.end(), by_x);
    fresh = {};

    std::int32_t* row = img.label.data() + static_cast<std::size_t>(j) * R;
    auto resolve = [&](int i0, int i1) {   // pixels [i0, i1), the IN set constant
      if (in.empty() || i0 >= i1) return;
      if (in.size() == 1) {
        std::fill(row + i0, row + i1, in[0].face);
        return;
      }
      const std::size_t left = nearest(w.cx(i0)), right = nearest(w.cx(i1 - 1));
      if (left == right) {
        std::fill(row + i0, row + i1, in[left].face);
        return;
      }
      for (int i = i0; i < i1; ++i) row[i] = in[nearest(w.cx(i))].face;
    };
    int next = 0;   // first pixel not yet resolved
    for (const Edge& e : ael) {
      const double t = std::ceil((e.x - w.x0) * inv - 0.5);
      const int at = t <= 0 ? 0 : t >= R ? R : static_cast<int>(t);   // first centre >= x
      if (at > next) {
        resolve(next, at);
        next = at;
      }
      toggle(e.piece);
    }
    // Each piece has an even number of crossings on a row, so every IN flag is
    // down again here; cleared anyway so that no rounding accident can leak.
    for (const In& p : in) slot[p.piece] = -1;
    in.clear();
  }
  return img;
}

}  // namespace vismap::raster
